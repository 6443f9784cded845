#pragma once
// CPU time of the calling thread: per-unit cost stays true when ranks share cores
// (DESIGN §3), unlike wall time. Wall time is for traces of phases.
#include <chrono>
#include <ctime>

namespace fe2 {

inline double thread_cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

inline double wall_seconds() {
  using clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

/// Accumulates CPU seconds into `sink` over its lifetime.
class ScopedCpuTimer {
 public:
  explicit ScopedCpuTimer(double& sink) : sink_(sink), t0_(thread_cpu_seconds()) {}
  ~ScopedCpuTimer() { sink_ += thread_cpu_seconds() - t0_; }
  ScopedCpuTimer(const ScopedCpuTimer&) = delete;
  ScopedCpuTimer& operator=(const ScopedCpuTimer&) = delete;

 private:
  double& sink_;
  double t0_;
};

/// Accumulates wall seconds into `sink` over its lifetime (a phase of a Newton iteration).
class ScopedWallTimer {
 public:
  explicit ScopedWallTimer(double& sink) : sink_(sink), t0_(wall_seconds()) {}
  ~ScopedWallTimer() { sink_ += wall_seconds() - t0_; }
  ScopedWallTimer(const ScopedWallTimer&) = delete;
  ScopedWallTimer& operator=(const ScopedWallTimer&) = delete;

 private:
  double& sink_;
  double t0_;
};

}  // namespace fe2
