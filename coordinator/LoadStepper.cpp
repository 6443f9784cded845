#include "coordinator/LoadStepper.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>

namespace fe2 {

namespace {

/// Growth after an easy sub-step (Abaqus/Standard's default factor for two easy increments).
constexpr double kGrowth = 1.5;

}  // namespace

LoadStepper::LoadStepper(const LoadStepOptions& options, double dt_nominal)
    : o_(options), dt_nominal_(dt_nominal), dt_(dt_nominal) {
  if (o_.max_dt <= 0.0) o_.max_dt = dt_nominal;
  if (o_.min_dt <= 0.0) o_.min_dt = dt_nominal / 1024.0;  // ten halvings of the whole step
  dt_ = std::min(dt_nominal, o_.max_dt);
}

void LoadStepper::begin_step() {
  cut_ = 0;
  if (!o_.adaptive) dt_ = dt_nominal_;
}

double LoadStepper::next_time(double t_n, double t_target) const {
  if (!o_.adaptive) return std::min(t_n + dt_nominal_ / std::ldexp(1.0, cut_), t_target);  // the fixed rule as it was
  const double rest = t_target - t_n;
  // The sub-steps left at Δt (a hair of slack: a rest of 2.0000000001 Δt is two steps).
  const double k = std::max(1.0, std::ceil(rest / dt_ * (1.0 - 1e-9)));
  return k == 1.0 ? t_target : t_n + rest / k;
}

void LoadStepper::converged(int iterations) {
  if (!o_.adaptive) return;
  if (iterations <= o_.target_iterations)
    dt_ = std::min(kGrowth * dt_, o_.max_dt);
  else
    dt_ = std::max(dt_ * o_.target_iterations / iterations, 0.5 * dt_);
}

bool LoadStepper::failed() {
  ++cut_;
  if (!o_.adaptive) return cut_ <= o_.max_cutbacks;
  dt_ *= 0.5;
  return dt_ >= o_.min_dt;
}

double LoadStepper::dt() const { return o_.adaptive ? dt_ : dt_nominal_ / std::ldexp(1.0, cut_); }

std::string LoadStepper::give_up_reason() const {
  if (!o_.adaptive) return fmt::format("after {} cutbacks", o_.max_cutbacks);
  return fmt::format("after {} cutbacks, the next below time.min_dt = {:.3g}", cut_, o_.min_dt);
}

}  // namespace fe2
