#include "coordinator/macro/LineSearch.h"

#include <algorithm>
#include <cmath>

namespace fe2 {

namespace {

/// Armijo's sufficient-decrease constant (Dennis & Schnabel's 1e-4).
constexpr double kArmijo = 1e-4;

}  // namespace

void LineSearch::start(double merit0) {
  merit0_ = merit0;
  alpha_ = 1.0;
  started_ = true;
}

LineSearch::Verdict LineSearch::judge(double merit) {
  if (!started_) return std::isfinite(merit) ? Verdict::take : Verdict::give_up;  // no correction to shorten
  if (std::isfinite(merit) && merit <= (1.0 - kArmijo * alpha_) * merit0_) return Verdict::take;
  double next = 0.5 * alpha_;
  if (std::isfinite(merit)) {
    // m(α) = φ(α)², m(0) = φ₀², m'(0) = −2φ₀²: the quadratic's minimiser, safeguarded.
    const double m0 = merit0_ * merit0_, slope = -2.0 * m0, ma = merit * merit;
    const double curvature = ma - m0 - slope * alpha_;
    const double quadratic = curvature > 0.0 ? -slope * alpha_ * alpha_ / (2.0 * curvature) : next;
    next = std::clamp(quadratic, 0.1 * alpha_, 0.5 * alpha_);
  }
  if (next < o_.min_step) {
    if (!std::isfinite(merit)) return Verdict::give_up;
    started_ = false;  // taken anyway: the next correction starts afresh
    return Verdict::take;
  }
  alpha_ = next;
  ++backtracks_;
  return Verdict::retry;
}

}  // namespace fe2
