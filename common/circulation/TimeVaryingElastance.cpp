#include "common/circulation/TimeVaryingElastance.h"

#include <cmath>
#include <numbers>

namespace fe2 {

double TimeVaryingElastance::activation(double t) const {
  double s = std::fmod(t - p_.onset, period_);
  if (s < 0.0) s += period_;
  constexpr double pi = std::numbers::pi;
  if (s < p_.contraction) return 0.5 * (1.0 - std::cos(pi * s / p_.contraction));
  s -= p_.contraction;
  if (s < p_.relaxation) return 0.5 * (1.0 + std::cos(pi * s / p_.relaxation));
  return 0.0;
}

}  // namespace fe2
