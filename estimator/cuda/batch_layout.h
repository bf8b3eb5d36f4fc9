#pragma once
// Host side of a batch of problems for the CUDA kernels (kernel_bodies.h): the concatenated
// hypothesis sets, probabilities and box sizes, and the prefix sums of BatchLayout. Plain C++:
// used by the CUDA backend (which uploads it) and by tests (which run the kernel bodies on it).
#include <cstdint>
#include <utility>
#include <vector>

#include "cuda/kernel_bodies.h"
#include "src/problem.h"

namespace criticality::cuda {

struct BatchHost {
  int problems{0};
  int steps{0};
  std::vector<core::HypothesisSet> sets;
  std::vector<int> set_base, ego_base{0}, co_base{0}, obj_base{0}, out_base{0};
  std::vector<long long> pair_base{0}, ego_obj_base{0};
  std::vector<int> co_object_of, co_offset;
  std::vector<double> co_half_length, co_half_width, ego_half_length, ego_half_width;
  std::vector<double> p_co, p_ego;

  /** Empty, keeping the vectors' memory (MakeBatch fills it again). */
  void Clear() {
    for (auto* v : {&set_base, &co_object_of, &co_offset}) v->clear();
    for (auto* v : {&ego_base, &co_base, &obj_base, &out_base}) v->assign(1, 0);
    for (auto* v : {&pair_base, &ego_obj_base}) v->assign(1, 0);
    for (auto* v : {&co_half_length, &co_half_width, &ego_half_length, &ego_half_width, &p_co,
                    &p_ego})
      v->clear();
    sets.clear();
  }

  int TotalEgo() const { return ego_base.back(); }
  int TotalCo() const { return co_base.back(); }
  long long TotalPairs() const { return pair_base.back(); }
  int TotalOut() const { return out_base.back(); }
  long long TotalEgoObj() const { return ego_obj_base.back(); }

  /** A layout whose pointers point into these host vectors. */
  BatchLayout HostView() const {
    return BatchLayout{problems,
                       steps,
                       TotalEgo(),
                       TotalCo(),
                       set_base.data(),
                       ego_base.data(),
                       co_base.data(),
                       pair_base.data(),
                       obj_base.data(),
                       ego_obj_base.data(),
                       out_base.data(),
                       co_object_of.data(),
                       co_offset.data(),
                       co_half_length.data(),
                       co_half_width.data(),
                       ego_half_length.data(),
                       ego_half_width.data()};
  }
};

/** Concatenates problems (all with the same number of steps) into *out, reusing its vectors'
 *  memory: a batch of a city's fleet is tens of MB, and fresh pages cost more to touch than
 *  the copy itself. */
inline void MakeBatch(const std::vector<const internal::Problem*>& problems, BatchHost* out) {
  BatchHost& b = *out;
  b.Clear();
  b.problems = static_cast<int>(problems.size());
  b.steps = problems.empty() ? 0 : problems.front()->Steps();
  size_t sets = 0, ego = 0, co = 0;
  for (const internal::Problem* pb : problems) {
    sets += 1 + pb->cos.size();
    ego += pb->EgoTrajectories();
    co += pb->CoTrajectories();
  }
  b.sets.reserve(sets);
  b.p_ego.reserve(ego);
  b.p_co.reserve(co);
  b.co_object_of.reserve(co);
  b.co_half_length.reserve(co);
  b.co_half_width.reserve(co);
  for (const internal::Problem* pb : problems) {
    const int n_ego = pb->EgoTrajectories(), n_co = pb->CoTrajectories();
    const int n_obj = static_cast<int>(pb->cos.size());
    b.set_base.push_back(static_cast<int>(b.sets.size()));
    b.sets.push_back(pb->ego);
    b.sets.insert(b.sets.end(), pb->cos.begin(), pb->cos.end());
    b.ego_base.push_back(b.ego_base.back() + n_ego);
    b.co_base.push_back(b.co_base.back() + n_co);
    b.obj_base.push_back(b.obj_base.back() + n_obj);
    b.pair_base.push_back(b.pair_base.back() + static_cast<long long>(n_ego) * n_co);
    b.ego_obj_base.push_back(b.ego_obj_base.back() + static_cast<long long>(n_ego) * n_obj);
    b.out_base.push_back(b.out_base.back() + b.steps + n_obj + 1);
    b.co_object_of.insert(b.co_object_of.end(), pb->co_object_of.begin(), pb->co_object_of.end());
    b.co_offset.insert(b.co_offset.end(), pb->co_offset.begin(), pb->co_offset.end() - 1);
    for (int j = 0; j < n_co; ++j) {
      b.co_half_length.push_back(pb->cos[pb->co_object_of[j]].half_length);
      b.co_half_width.push_back(pb->cos[pb->co_object_of[j]].half_width);
    }
    b.ego_half_length.push_back(pb->ego.half_length);
    b.ego_half_width.push_back(pb->ego.half_width);
    b.p_co.insert(b.p_co.end(), pb->co_probability.begin(), pb->co_probability.end());
    b.p_ego.insert(b.p_ego.end(), pb->ego_probability.begin(), pb->ego_probability.end());
  }
}

inline BatchHost MakeBatch(const std::vector<const internal::Problem*>& problems) {
  BatchHost b;
  MakeBatch(problems, &b);
  return b;
}

/** The device memory one problem takes in a batch, as CudaBackend allocates it: its hypothesis
 *  sets and batch offsets; per ego and CO trajectory and step the poses (x, y, yaw, cos, sin);
 *  per ego x CO trajectory pair the first colliding step (int16), the risk's event slot (int)
 *  and contribution (double): 14 bytes a pair; per ego trajectory its probability, histogram
 *  (steps + 1 ints), sums by step, collision probability and hit mark; the bounds of
 *  every trajectory per block of steps (4 doubles); per ego trajectory x
 *  object the hit mass and sums by object; per CO trajectory its index, box and probability;
 *  its outputs. A batch takes the sum over its problems. */
inline std::uint64_t DeviceBytes(const internal::Problem& pb) {
  const std::uint64_t steps = static_cast<std::uint64_t>(pb.Steps());
  const std::uint64_t ego = static_cast<std::uint64_t>(pb.EgoTrajectories());
  const std::uint64_t co = static_cast<std::uint64_t>(pb.CoTrajectories());
  const std::uint64_t obj = pb.cos.size();
  const std::uint64_t d = sizeof(double);
  std::uint64_t b = (1 + obj) * sizeof(core::HypothesisSet);   // sets
  b += 7 * sizeof(int) + 2 * sizeof(long long) + 2 * d;        // offsets, ego box
  b += (ego + co) * steps * 5 * d;                             // poses
  b += (ego + co) * BoundsBlocks(pb.Steps()) * 4 * d;          // their bounds per block
  b += ego * co * (sizeof(std::int16_t) + sizeof(int) + d);    // pair matrix, risk scratch
  b += ego * (d + (steps + 1) * sizeof(int) + steps * d + d + 1);
  b += ego * obj * 2 * d;                                      // hit mass, sums by object
  b += co * (sizeof(int) + 3 * d) + obj * sizeof(int);         // CO index, box, p; offsets
  b += (steps + obj + 1) * d;                                  // outputs
  return b;
}

/** Consecutive chunks [first, last) of problems whose DeviceBytes (`bytes`) add up to at most
 *  `budget`, in order, covering every problem; a problem over the budget alone is a chunk of its
 *  own (its allocation then fails with a CudaError that names what could not be allocated). */
inline std::vector<std::pair<size_t, size_t>> BatchChunks(const std::vector<std::uint64_t>& bytes,
                                                          std::uint64_t budget) {
  std::vector<std::pair<size_t, size_t>> out;
  size_t first = 0;
  std::uint64_t sum = 0;
  for (size_t k = 0; k < bytes.size(); ++k) {
    if (k > first && sum + bytes[k] > budget) {
      out.emplace_back(first, k);
      first = k;
      sum = 0;
    }
    sum += bytes[k];
  }
  if (first < bytes.size()) out.emplace_back(first, bytes.size());
  return out;
}

}  // namespace criticality::cuda
