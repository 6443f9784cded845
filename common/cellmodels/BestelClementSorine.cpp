#include "common/cellmodels/BestelClementSorine.h"

#include "common/cellmodels/cell_integrator.h"
#include "common/error.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace fe2 {

BestelClementSorine::BestelClementSorine(const BestelClementSorineParameters& p,
                                         const CalciumParameters& calcium, double max_substep)
    : p_(p), calcium_(calcium), max_substep_(max_substep) {
  FE2_CHECK(p.sigma_0 > 0.0 && p.alpha_max > 0.0 && p.alpha_min < 0.0,
            "need sigma_0 > 0, alpha_max > 0, alpha_min < 0; got {}, {}, {}", p.sigma_0,
            p.alpha_max, p.alpha_min);
  FE2_CHECK(max_substep > 0.0, "max_substep {} must be > 0", max_substep);
}

std::string BestelClementSorine::description() const {
  return fmt::format(
      "bestel_clement_sorine (Bestel et al. 2001, as in Pfaller et al. 2019): sigma_0 = {} kPa, "
      "alpha_max = {}/s, alpha_min = {}/s; {}; RK4 substeps <= {} s",
      1e-3 * p_.sigma_0, p_.alpha_max, p_.alpha_min, calcium_.description(), max_substep_);
}

void BestelClementSorine::rest_state(std::span<double> state) const {
  FE2_CHECK(state.size() == 1, "state size {}", state.size());
  state[0] = 0.0;  // f = 0 at rest: u = α_min < 0 relaxes τ_c to 0
}

ActiveTension BestelClementSorine::advance(const CellStep& step, std::span<const double> committed,
                                           std::span<double> current) const {
  std::array<double, 1> y{committed[0]};
  if (step.dt > 0.0) {
    const double rest = calcium_.parameters().rest;
    const double scale = 1.0 / (calcium_.parameters().peak - rest);
    integrate_rk4(step, calcium_, max_substep_, y,
                  [&](double, double ca, double, double, const std::array<double, 1>& z,
                      std::array<double, 1>& dz) {
                    const double f = (ca - rest) * scale;
                    const double u = p_.alpha_max * f + p_.alpha_min * (1.0 - f);
                    dz[0] = -std::abs(u) * z[0] + p_.sigma_0 * std::max(u, 0.0);
                  });
  }
  current[0] = y[0];
  return {y[0], 0.0, 0.0};
}

}  // namespace fe2
