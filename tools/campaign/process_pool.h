#pragma once
// A pool of child processes (one run each): fork/exec with the child in its own process group,
// its working directory, stdout and stderr redirected to files, stdin from /dev/null, and
// PR_SET_PDEATHSIG so that it dies with the pool. A time limit per child: SIGTERM to its
// group, SIGKILL `kill_after_s` later. Waiting uses sigtimedwait on SIGCHLD (blocked while the
// pool exists), so a finished child is noticed at once, without polling.
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace criticality::campaign {

struct ChildSpec {
  std::size_t id{0};  ///< the caller's tag (the run index)
  std::vector<std::string> argv;
  std::filesystem::path cwd;
  std::filesystem::path stdout_path;
  std::filesystem::path stderr_path;
};

struct ChildResult {
  std::size_t id{0};
  int exit_code{-1};      ///< -1 when killed by a signal
  int signal{0};          ///< the terminating signal, 0 when it exited
  bool timed_out{false};  ///< the pool stopped it at the time limit
  bool stopped{false};    ///< the pool stopped it in StopAll()
  double wall_s{0.0};
  long max_rss_kb{0};
};

class ProcessPool {
 public:
  /** `time_limit_s` <= 0: no limit. */
  ProcessPool(int slots, double time_limit_s, double kill_after_s);
  ~ProcessPool();  ///< kills and reaps what still runs
  ProcessPool(const ProcessPool&) = delete;
  ProcessPool& operator=(const ProcessPool&) = delete;

  int slots() const { return slots_; }
  std::size_t running() const { return children_.size(); }
  bool full() const { return static_cast<int>(children_.size()) >= slots_; }

  /** Starts a child. Throws std::runtime_error when fork fails. A program that cannot be
   *  executed ends with exit code 127 and the reason in its stderr file. */
  void Start(const ChildSpec& spec);

  /** Returns the children that ended (at least one, unless `max_wait_s` passed or a signal
   *  handler interrupted the wait), enforcing time limits meanwhile. */
  std::vector<ChildResult> Wait(double max_wait_s);

  /** SIGTERM to every child's group, SIGKILL to those still there after kill_after_s; reaps
   *  them all. Results have `stopped` set. */
  std::vector<ChildResult> StopAll();

 private:
  using Clock = std::chrono::steady_clock;
  struct Child {
    pid_t pid{0};
    std::size_t id{0};
    Clock::time_point start;
    bool term_sent{false};
    bool timed_out{false};
    bool stopped{false};
    Clock::time_point kill_at;
  };
  std::vector<ChildResult> Reap();
  void EnforceLimits(Clock::time_point now);
  Clock::time_point NextDeadline(Clock::time_point fallback) const;

  int slots_;
  double time_limit_s_;
  double kill_after_s_;
  std::vector<Child> children_;
  sigset_t old_mask_{};
};

}  // namespace criticality::campaign
