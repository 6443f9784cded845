#pragma once
// The sub-steps that carry the committed state from one output step's start to its end
// (time.steps fixes the output times, t_end·k/steps; the sub-steps are the stepper's).
//
// Fixed (time.adaptive false, the default): the step is tried whole; a failure halves it,
// up to newton.max_cutbacks times, and the halved size holds to the end of the step. This
// is the stepping every run had before the adaptive stepper, bit for bit.
//
// Adaptive (time.adaptive true): the size follows Newton's behaviour and carries over from
// one output step to the next, as in the automatic incrementation of Abaqus/Standard and
// FEBio's auto-stepper:
//   converged in n ≤ target iterations    Δt ← min(1.5 Δt, max_dt)
//   converged in n > target iterations    Δt ← max(Δt · target/n, Δt/2)
//   failed (no convergence, inversion…)   Δt ← Δt/2; give up below min_dt
// Each sub-step ends at t_n + (t_target − t_n)/k with k = ⌈(t_target − t_n)/Δt⌉, so the
// output time is hit exactly and no sliver step is left before it. The decisions use
// only iteration counts and failures, which every coordinator shares: the step sequence
// is the same on any number of ranks.
#include <string>

namespace fe2 {

struct LoadStepOptions {
  bool adaptive = false;
  double max_dt = 0.0;         ///< > 0: largest sub-step (adaptive)
  double min_dt = 0.0;         ///< > 0: the adaptive stepper gives up below this
  int target_iterations = 8;   ///< adaptive: Newton iterations a sub-step should take
  int max_cutbacks = 4;        ///< fixed: halvings of one step before giving up
};

class LoadStepper {
 public:
  /// `dt_nominal`: t_end / steps.
  LoadStepper(const LoadStepOptions& options, double dt_nominal);

  /// At the start of each output step (fixed: back to the whole step).
  void begin_step();
  /// The end of the next sub-step from the committed time t_n (< t_target).
  double next_time(double t_n, double t_target) const;
  /// A sub-step of `iterations` Newton iterations converged.
  void converged(int iterations);
  /// A sub-step failed; false when the stepper gives up (the caller then stops).
  bool failed();
  /// The next sub-step's size before it is fitted to the output time (for the log).
  double dt() const;
  /// Why failed() gave up: "after 4 cutbacks", "below time.min_dt = 1e-05".
  std::string give_up_reason() const;
  /// Failures since the output step began.
  int cutbacks() const { return cut_; }

 private:
  LoadStepOptions o_;
  double dt_nominal_;
  double dt_;      ///< adaptive: the current sub-step size
  int cut_ = 0;    ///< failures in this output step (fixed: the halvings)
};

}  // namespace fe2
