#pragma once
// A heart valve as a smooth diode. With Δp = p_up − p_down, G_o = 1/R_open,
// G_c = 1/R_closed and a switching width w (Pa):
//   Q(Δp) = G_c Δp + (G_o − G_c) w ln(1 + exp(Δp / w))              (mm³/s)
//   dQ/dΔp = G_c + (G_o − G_c) σ(Δp / w),   σ(x) = 1 / (1 + e^{−x}).
// Q → Δp/R_open for Δp ≫ w and Q → Δp/R_closed for Δp ≪ −w; the equivalent resistance
// R(Δp) = Δp/Q moves smoothly from R_closed to R_open over a few w. Unlike a blend of
// the resistances themselves (Regazzoni et al. 2022 blend log R with an arctan), dQ/dΔp
// stays in [G_c, G_o]: Q is monotone and convex in Δp, so every Newton solve through an
// opening or closing valve has one solution and converges. The valve counts as open
// when Δp > 0.
#include <cmath>

namespace fe2 {

struct ValveParameters {
  double R_open = 0.0;    ///< Pa·s/mm³
  double R_closed = 0.0;  ///< Pa·s/mm³, > R_open
  double width = 0.0;     ///< w (Pa)
};

struct ValveFlow {
  double Q = 0.0;      ///< mm³/s
  double dQ = 0.0;     ///< dQ/dΔp (mm³/(s·Pa))
};

/// Q and dQ/dΔp at Δp = p_up − p_down (softplus and σ evaluated without overflow).
inline ValveFlow valve_flow(const ValveParameters& v, double dp) {
  const double Go = 1.0 / v.R_open, Gc = 1.0 / v.R_closed;
  const double x = dp / v.width;
  const double softplus = x > 0.0 ? x + std::log1p(std::exp(-x)) : std::log1p(std::exp(x));
  const double sigma = x > 0.0 ? 1.0 / (1.0 + std::exp(-x)) : std::exp(x) / (1.0 + std::exp(x));
  return {Gc * dp + (Go - Gc) * v.width * softplus, Gc + (Go - Gc) * sigma};
}

}  // namespace fe2
