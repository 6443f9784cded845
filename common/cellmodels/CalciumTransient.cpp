#include "common/cellmodels/CalciumTransient.h"

#include "common/error.h"

#include <cmath>
#include <limits>

namespace fe2 {

CalciumTransient::CalciumTransient(const CalciumParameters& p) : p_(p) {
  FE2_CHECK(p.rise > 0.0 && p.rise < p.decay, "need 0 < rise < decay, got rise {} s, decay {} s",
            p.rise, p.decay);
  FE2_CHECK(p.rest > 0.0 && p.peak > p.rest, "need 0 < rest < peak, got rest {} µM, peak {} µM",
            p.rest, p.peak);
  FE2_CHECK(p.period >= 0.0, "need period >= 0, got {} s", p.period);
  s_peak_ = p.rise * p.decay * std::log(p.decay / p.rise) / (p.decay - p.rise);
  inv_norm_ = 1.0 / (std::exp(-s_peak_ / p.decay) - std::exp(-s_peak_ / p.rise));
}

double CalciumTransient::shape(double s) const {
  return (std::exp(-s / p_.decay) - std::exp(-s / p_.rise)) * inv_norm_;
}

double CalciumTransient::activation(double t, double t_act) const {
  double s = t - t_act;
  if (s < 0.0) return 0.0;
  if (p_.period > 0.0) s = std::fmod(s, p_.period);
  return shape(s);
}

double CalciumTransient::value(double t, double t_act) const {
  return p_.rest + (p_.peak - p_.rest) * activation(t, t_act);
}

double CalciumTransient::next_onset(double t, double t_act) const {
  if (t < t_act) return t_act;
  if (p_.period <= 0.0) return std::numeric_limits<double>::infinity();
  const double k = std::floor((t - t_act) / p_.period) + 1.0;
  return t_act + k * p_.period;
}

std::string CalciumTransient::description() const {
  return fmt::format("bi-exponential calcium: rest {} µM, peak {} µM, rise {} ms, decay {} ms, {}",
                     p_.rest, p_.peak, 1e3 * p_.rise, 1e3 * p_.decay,
                     p_.period > 0.0 ? fmt::format("period {} s", p_.period)
                                     : std::string("one beat"));
}

}  // namespace fe2
