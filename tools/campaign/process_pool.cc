#include "tools/campaign/process_pool.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace criticality::campaign {
namespace {

// Writes a message without allocating (between fork and exec).
void ChildFail(const char* what, int err) {
  const char* msg = std::strerror(err);
  (void)!::write(2, "criticality-campaign: ", 22);
  (void)!::write(2, what, std::strlen(what));
  (void)!::write(2, ": ", 2);
  (void)!::write(2, msg, std::strlen(msg));
  (void)!::write(2, "\n", 1);
  ::_exit(127);
}

}  // namespace

ProcessPool::ProcessPool(int slots, double time_limit_s, double kill_after_s)
    : slots_(std::max(1, slots)), time_limit_s_(time_limit_s), kill_after_s_(kill_after_s) {
  sigset_t chld;
  sigemptyset(&chld);
  sigaddset(&chld, SIGCHLD);
  sigprocmask(SIG_BLOCK, &chld, &old_mask_);
}

ProcessPool::~ProcessPool() {
  for (const Child& c : children_) ::kill(-c.pid, SIGKILL);
  for (const Child& c : children_) {
    int status = 0;
    while (::waitpid(c.pid, &status, 0) < 0 && errno == EINTR) {
    }
  }
  sigprocmask(SIG_SETMASK, &old_mask_, nullptr);
}

void ProcessPool::Start(const ChildSpec& spec) {
  // Everything the child needs is prepared before fork: after it, only async-signal-safe calls.
  std::vector<char*> argv;
  argv.reserve(spec.argv.size() + 1);
  for (const std::string& a : spec.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const std::string cwd = spec.cwd.string();
  const std::string out = spec.stdout_path.string();
  const std::string err = spec.stderr_path.string();
  const pid_t parent = ::getpid();

  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
  if (pid == 0) {
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);  // the pool died before prctl
    for (int s : {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGCHLD}) ::signal(s, SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    const int fe = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fe < 0 || ::dup2(fe, 2) < 0) ChildFail("cannot open stderr file", errno);
    const int fo = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fo < 0 || ::dup2(fo, 1) < 0) ChildFail("cannot open stdout file", errno);
    const int fi = ::open("/dev/null", O_RDONLY);
    if (fi < 0 || ::dup2(fi, 0) < 0) ChildFail("cannot open /dev/null", errno);
    for (int fd : {fe, fo, fi}) {
      if (fd > 2) ::close(fd);
    }
    if (!cwd.empty() && ::chdir(cwd.c_str()) != 0) ChildFail("cannot enter the run folder", errno);
    ::execv(argv[0], argv.data());
    ChildFail(argv[0], errno);
  }
  ::setpgid(pid, pid);  // also here, so that the group exists before any kill(-pid)
  Child c;
  c.pid = pid;
  c.id = spec.id;
  c.start = Clock::now();
  children_.push_back(c);
}

std::vector<ChildResult> ProcessPool::Reap() {
  std::vector<ChildResult> done;
  while (!children_.empty()) {
    int status = 0;
    rusage usage{};
    const pid_t pid = ::wait4(-1, &status, WNOHANG, &usage);
    if (pid <= 0) break;
    const auto it = std::find_if(children_.begin(), children_.end(),
                                 [&](const Child& c) { return c.pid == pid; });
    if (it == children_.end()) continue;  // not ours
    ChildResult r;
    r.id = it->id;
    r.wall_s = std::chrono::duration<double>(Clock::now() - it->start).count();
    r.max_rss_kb = usage.ru_maxrss;
    r.timed_out = it->timed_out;
    r.stopped = it->stopped;
    if (WIFEXITED(status)) {
      r.exit_code = WEXITSTATUS(status);
    } else if (WIFSIGNALED(status)) {
      r.signal = WTERMSIG(status);
    }
    // Whatever the run left in its group (helpers it started) goes with it.
    ::kill(-pid, SIGKILL);
    children_.erase(it);
    done.push_back(r);
  }
  return done;
}

void ProcessPool::EnforceLimits(Clock::time_point now) {
  for (Child& c : children_) {
    if (!c.term_sent && time_limit_s_ > 0.0 &&
        now - c.start >= std::chrono::duration<double>(time_limit_s_)) {
      ::kill(-c.pid, SIGTERM);
      c.term_sent = true;
      c.timed_out = true;
      c.kill_at = now + std::chrono::duration_cast<Clock::duration>(
                            std::chrono::duration<double>(kill_after_s_));
    }
    if (c.term_sent && now >= c.kill_at) ::kill(-c.pid, SIGKILL);
  }
}

ProcessPool::Clock::time_point ProcessPool::NextDeadline(Clock::time_point fallback) const {
  Clock::time_point next = fallback;
  for (const Child& c : children_) {
    if (c.term_sent) {
      next = std::min(next, c.kill_at);
    } else if (time_limit_s_ > 0.0) {
      next = std::min(next, c.start + std::chrono::duration_cast<Clock::duration>(
                                          std::chrono::duration<double>(time_limit_s_)));
    }
  }
  return next;
}

std::vector<ChildResult> ProcessPool::Wait(double max_wait_s) {
  const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(std::max(0.0, max_wait_s)));
  sigset_t chld;
  sigemptyset(&chld);
  sigaddset(&chld, SIGCHLD);
  while (true) {
    std::vector<ChildResult> done = Reap();
    if (!done.empty() || children_.empty()) return done;
    const auto now = Clock::now();
    EnforceLimits(now);
    const auto next = NextDeadline(until);
    if (now >= until) return done;
    const auto wait = std::max(next - now, Clock::duration(std::chrono::milliseconds(1)));
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(wait).count();
    timespec ts{static_cast<time_t>(ns / 1'000'000'000), static_cast<long>(ns % 1'000'000'000)};
    if (::sigtimedwait(&chld, nullptr, &ts) < 0 && errno == EINTR) return Reap();
  }
}

std::vector<ChildResult> ProcessPool::StopAll() {
  const auto now = Clock::now();
  const auto kill_at = now + std::chrono::duration_cast<Clock::duration>(
                                 std::chrono::duration<double>(kill_after_s_));
  for (Child& c : children_) {
    ::kill(-c.pid, SIGTERM);
    c.stopped = true;
    if (!c.term_sent || c.kill_at > kill_at) c.kill_at = kill_at;
    c.term_sent = true;
  }
  std::vector<ChildResult> all;
  sigset_t chld;
  sigemptyset(&chld);
  sigaddset(&chld, SIGCHLD);
  while (!children_.empty()) {
    for (ChildResult& r : Reap()) all.push_back(r);
    if (children_.empty()) break;
    EnforceLimits(Clock::now());
    timespec ts{0, 50'000'000};
    ::sigtimedwait(&chld, nullptr, &ts);
  }
  return all;
}

}  // namespace criticality::campaign
