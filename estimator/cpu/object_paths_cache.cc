#include "cpu/object_paths_cache.h"

#include <cstring>
#include <type_traits>

#include "cpu/sibling_steps.h"

namespace criticality::internal {

static_assert(std::is_trivially_copyable_v<core::HypothesisSet>,
              "the cache key is the set's bytes");
static_assert(std::is_trivially_copyable_v<core::SimulationConfig>,
              "the cache key is the settings' bytes");

std::string ObjectPathsCache::KeyOf(const core::HypothesisSet& h, const core::SimulationConfig& sim,
                                    char mode) {
  std::string key(sizeof(h) + sizeof(sim) + 1, '\0');
  std::memcpy(&key[0], &h, sizeof(h));
  std::memcpy(&key[sizeof(h)], &sim, sizeof(sim));
  key.back() = mode;
  return key;
}

std::shared_ptr<const ObjectPathsCache::Paths> ObjectPathsCache::Find(
    const std::string& key) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = entries_.find(key);
  if (it == entries_.end()) {
    ++misses_;
    return nullptr;
  }
  ++hits_;
  return it->second;
}

void ObjectPathsCache::Store(std::string key, std::shared_ptr<const Paths> paths) {
  const size_t bytes = EntryBytes(paths->x.size());
  std::lock_guard<std::mutex> lock(mutex_);
  if (stored_bytes_ + bytes > capacity_bytes_) return;
  if (entries_.emplace(std::move(key), std::move(paths)).second) stored_bytes_ += bytes;
}

bool ObjectPathsCache::HasRoom(int trajectories, int steps) const {
  const size_t bytes = EntryBytes(static_cast<size_t>(trajectories) * steps);
  std::lock_guard<std::mutex> lock(mutex_);
  return stored_bytes_ + bytes <= capacity_bytes_;
}

void ObjectPathsCache::Clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  entries_.clear();
  stored_bytes_ = 0;
}

long long ObjectPathsCache::Hits() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return hits_;
}

long long ObjectPathsCache::Misses() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return misses_;
}

std::shared_ptr<const ObjectPathsCache::Paths> SimulateLanePaths(
    const core::HypothesisSet& h, const core::SimulationConfig& sim) {
  auto p = std::make_shared<ObjectPathsCache::Paths>();
  const int steps = sim.n_steps;
  const size_t n = static_cast<size_t>(h.Trajectories()) * steps;
  p->steps = steps;
  for (std::vector<double>* v : {&p->x, &p->y, &p->yaw, &p->c, &p->s}) v->resize(n);
  for (int profile = 0; profile < h.n_profiles; ++profile) {
    const size_t at = static_cast<size_t>(profile) * h.n_paths * steps;
    SimulateProfilePaths(h, sim, profile, &p->x[at], &p->y[at], &p->yaw[at], steps, &p->c[at],
                         &p->s[at]);
  }
  return p;
}

}  // namespace criticality::internal
