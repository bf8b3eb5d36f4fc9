#pragma once
// Other road users simulated once per batch (issue 23). In a fleet every vehicle is an object
// in its neighbours' scenes, and each of those scenes builds the same hypothesis set for it
// (its state and lanes come from the simulator once per step): on one recorded city step
// (bench/RESULTS.md) 388 scenes held 1,790 object sets, 380 of them distinct. The CPU backend
// looks a set up here before simulating it and stores what it simulated, so a batch simulates
// each distinct set once.
//
// Exact by construction: the key is the set's and the simulation settings' bytes, compared in
// full (not a hash), so a hit hands out the poses and cos/sin that simulating the set in this
// process gives, bit for bit. A set that differs in any byte (padding included) is simply
// simulated again.
//
// Shared by the batch's workers (ScenePool), guarded by a mutex; entries are immutable once
// stored. Memory is bounded: once the stored poses reach the capacity, nothing more is stored
// (the sets that do not fit are simulated in each scene, as without the cache). The owner
// clears it at the end of every batch, so it holds one fleet step at most.
#include <cstddef>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/hypothesis_set.h"
#include "core/trajectory_generation.h"

namespace criticality::internal {

class ObjectPathsCache {
 public:
  /** Every trajectory of one set (profile-major, as the backend's store: trajectory t =
   *  profile * n_paths + path at [t * steps + n]): poses in the scene frame and the cos/sin of
   *  each pose's heading. */
  struct Paths {
    int steps{0};
    std::vector<double> x, y, yaw, c, s;
  };

  explicit ObjectPathsCache(size_t capacity_bytes) : capacity_bytes_(capacity_bytes) {}

  /** What identifies a simulation: the set, the settings, and which code simulated it (`mode`:
   *  the backend's SIMD or scalar path, whose poses differ within rounding). */
  static std::string KeyOf(const core::HypothesisSet& h, const core::SimulationConfig& sim,
                           char mode);

  /** The paths stored under `key`, or null. */
  std::shared_ptr<const Paths> Find(const std::string& key) const;
  /** Stores `paths` under `key` unless the key is there already or the capacity is reached. */
  void Store(std::string key, std::shared_ptr<const Paths> paths);
  /** Whether a set of `trajectories` x `steps` poses would still fit: callers skip copying
   *  (or simulating a set whole) for a store that would be refused. */
  bool HasRoom(int trajectories, int steps) const;
  /** Forgets every entry (the end of a batch). */
  void Clear();

  /** Lookups that found an entry, and that did not, since construction (for reports). */
  long long Hits() const;
  long long Misses() const;

 private:
  size_t capacity_bytes_;
  mutable std::mutex mutex_;
  std::unordered_map<std::string, std::shared_ptr<const Paths>> entries_;
  size_t stored_bytes_{0};
  // What an entry of that many poses takes: its five arrays and its key (KeyOf).
  static size_t EntryBytes(size_t poses) {
    return 5 * sizeof(double) * poses + sizeof(core::HypothesisSet) +
           sizeof(core::SimulationConfig) + 1;
  }
  mutable long long hits_{0}, misses_{0};
};

/** Every trajectory of `h` (a set SiblingStepsApply covers) simulated in SIMD lanes with
 *  its cos/sin, as the CPU backend simulates such a set with simd on (key mode 1): for the
 *  reach shortcut, which stores what it simulated for the backend to copy. */
std::shared_ptr<const ObjectPathsCache::Paths> SimulateLanePaths(const core::HypothesisSet& h,
                                                                 const core::SimulationConfig& sim);

}  // namespace criticality::internal
