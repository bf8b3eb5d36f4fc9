#pragma once
/** @file The estimator: one object, several backends behind the same interface. */
#include <memory>
#include <string>
#include <vector>

#include "criticality/params.h"
#include "criticality/result.h"
#include "criticality/scene.h"

namespace criticality {

/** Which implementation runs the four modules. */
enum class Backend {
  kReference,  ///< the plain literal algorithm: one thread, every pair at every step, no pruning.
               ///< The judge of every faster path.
  kCpu,        ///< CPU fast path: shared path prefixes, swept bounds, threads, early exit.
  kCuda,       ///< NVIDIA GPU: every hypothesis and pair in parallel (needs a usable device).
  kAuto,       ///< kCuda when a device is usable, else kCpu (saying so once on stderr).
};

/** Parses "reference" / "cpu" / "cuda" / "auto"; throws InputError naming the accepted values. */
Backend ParseBackend(const std::string& name);
std::string BackendName(Backend backend);

/** True when this build has CUDA and a device can be used; otherwise `why` says what is
 *  missing (no CUDA in this build, no device, driver too old...). */
bool CudaUsable(std::string* why);

/** Empty when the estimator can use `lane` as given (its dividers define y(x) in the observer's
 *  frame turned by frame_rad, see LaneFrameAngle, as Lane::straight_to_middle asks when set,
 *  and the lane has a positive width at the observer); otherwise why not. Lets a caller that
 *  builds lanes from a map (the SUMO driver) leave out a lane instead of failing the estimate. */
std::string LaneProblem(const Lane& lane, double frame_rad = 0.0);

/** How far the centre line the estimator fits to `lane` (in the frame turned by frame_rad, as
 *  LaneProblem) lies from `centre`, points of the lane's true centre line in the observer's
 *  frame: the largest gap along the fitted frame's y axis, taken across the curve (times the
 *  cosine of its slope there), over the points whose x in that frame lies within the lane's
 *  samples. Lets a caller that samples lanes from a map see
 *  a parabola that leaves the lane between its samples. `lane` must be usable (LaneProblem
 *  empty). */
double LaneCentreDeviation(const Lane& lane, double frame_rad, const std::vector<Point2>& centre);

/** The frame the estimator fits an observer's `lanes` in, as an angle from its heading: 0, or
 *  the direction of its own lane's chord when that lane turns across its heading
 *  (Params::turn_lane_frame). */
double LaneFrameAngle(const LaneSet& lanes, const Params& params);

/** Execution settings (not part of the algorithm). */
struct EstimatorOptions {
  Backend backend{Backend::kCpu};
  /** Worker threads for the cpu backend (on one estimate, or on a batch's scenes: see
   *  Estimator::EstimateBatch); 0 = hardware concurrency. */
  int threads{0};
  /** Keep Result::first_collision_step (2 bytes per ego x CO trajectory pair). */
  bool keep_pair_matrix{false};
  /** The exact reach shortcut (src/reach_filter.h): collision objects that cannot come near
   *  any ego hypothesis within the horizon are left out (ObjectResult::out_of_reach), and a
   *  scene with no object left is answered without generating trajectories. Changes no
   *  probability; the pair matrix then holds only the kept objects' columns. */
  bool reach_shortcut{false};
  /** cpu backend: simulate sibling ego paths in SIMD lanes and take the poses' cos/sin from
   *  vector math (cpu/sibling_steps.h). Within 3 ulp of libm per call, so the pair matrix may
   *  differ from the reference's in grazing contacts; false: the scalar code, bit for bit the
   *  reference's pair matrix. */
  bool simd{true};
  /** cpu backend: ego subtrees whose reach meets no object are neither simulated nor checked
   *  (cpu/cpu_backend.h). Changes nothing in the result; false: every ego path is simulated
   *  (for comparing the cost). */
  bool skip_out_of_reach{true};
  /** cpu backend on more than one thread: between an estimate's parallel loops the helper
   *  threads (and the caller waiting for them) spin for up to 250 us before they sleep
   *  (src/parallel_for.h: waking a sleeping thread costs tens of microseconds). false: they
   *  sleep at once, for callers that share the cores with other work meanwhile (the pipelined
   *  driver, where SUMO's step runs beside the estimate). */
  bool spin_wait{true};
  /** cpu backend, batches (Estimator::EstimateBatch): another road user whose hypothesis set
   *  several scenes of the batch share (a fleet's neighbours see the same vehicle) is simulated
   *  in one of them and copied to the others (cpu/object_paths_cache.h), up to this many MiB of
   *  stored poses per batch. Changes nothing in the result; 0: every scene simulates its own
   *  (for comparing the cost). */
  int shared_object_paths_mib{256};
};

class EstimatorBackend;
class ScenePool;
namespace internal {
class ObjectPathsCache;
}

/** Estimates the criticality of scenes. Reuses its buffers across calls; not thread-safe (use
 *  one Estimator per thread). With the cpu backend and threads() > 1 it also keeps a pool of
 *  threads() - 1 threads for batches (EstimateBatch), started at the first batch that needs
 *  it and stopped with the Estimator. */
class Estimator {
 public:
  /** @throws InputError when params are invalid, or the cuda backend is asked for and no
   *  device is usable (the message says why). */
  explicit Estimator(const Params& params, const EstimatorOptions& options = {});
  ~Estimator();
  Estimator(const Estimator&) = delete;
  Estimator& operator=(const Estimator&) = delete;

  /** Runs street data processing, trajectory generation, collision recognition and risk
   *  assessment on one scene.
   *  @throws InputError when the scene is invalid (the message names the field and value).
   *  @throws WorkloadError when the work would exceed Params::max_memory_bytes. */
  Result Estimate(const Scene& scene);

  /** Estimates many scenes (e.g. every vehicle of a network as ego) with the same params and
   *  backend, in one call; results[k] belongs to scenes[k] and is what Estimate(scenes[k])
   *  gives, bit for bit, whatever the backend's split of the work (only Result::times differ).
   *  - cuda: the whole batch in one set of kernel launches; module times are per-scene means.
   *  - cpu with threads() > 1: the scenes are spread over threads() workers (this thread and
   *    a persistent pool, cpu/scene_pool.h), each with its own single-threaded estimator,
   *    taking chunks of 2 scenes in turn; times are each scene's own. A batch of one scene
   *    gets every thread, as Estimate() does, unless its hypothesis set is small (ego
   *    hypothesis steps profiles * TimeSteps * LateralSamplesThreeLanes^instants < 5e4): then
   *    one thread, which is faster than splitting so little work.
   *  - reference, or cpu on one thread: one scene after the other; street and total times
   *    are per-scene means.
   *  @throws InputError or WorkloadError as Estimate() does, for the first failing scene in
   *  batch order (on the cpu pool, the rest of the batch is then abandoned; the Estimator
   *  stays usable). */
  std::vector<Result> EstimateBatch(const std::vector<Scene>& scenes);

  const Params& params() const { return params_; }
  const EstimatorOptions& options() const { return options_; }
  /** Threads the backend actually uses (options().threads resolved). */
  int threads() const;

 private:
  Params params_;
  EstimatorOptions options_;
  std::unique_ptr<EstimatorBackend> backend_;
  /** Other road users' paths shared by the scenes of one batch (options_.shared_object_paths_mib;
   *  null when off or not a cpu backend); the pool has its own for its workers. */
  std::unique_ptr<internal::ObjectPathsCache> paths_cache_;
  /** The cache of the batch being estimated (null: none), for the reach shortcut and the
   *  backend: paths_cache_ during EstimateBatch, the pool's for a pool's worker. */
  internal::ObjectPathsCache* batch_paths_{nullptr};
  void SharePaths(internal::ObjectPathsCache* cache);
  friend class ScenePool;            // shares one ObjectPathsCache among its workers' backends
  std::unique_ptr<ScenePool> pool_;  ///< cpu batches on threads() > 1, made at the first one
};

}  // namespace criticality
