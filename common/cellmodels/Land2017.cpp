#include "common/cellmodels/Land2017.h"

#include "common/cellmodels/Dual.h"
#include "common/cellmodels/cell_integrator.h"
#include "common/error.h"

#include <algorithm>
#include <cmath>

namespace fe2 {

Land2017Parameters Land2017Parameters::intact() { return {}; }

Land2017Parameters Land2017Parameters::skinned() {
  Land2017Parameters p;
  p.ca50_ref = 2.5;
  p.n_tm = 2.2;
  p.k_uw = 26.0;
  p.k_ws = 4.0;
  p.T_ref = 40.5e3;
  return p;
}

Land2017::Land2017(const Land2017Parameters& p, const CalciumParameters& calcium,
                   double max_substep, std::string set_name, std::string overridden)
    : p_(p), calcium_(calcium), max_substep_(max_substep), set_name_(std::move(set_name)),
      overridden_(std::move(overridden)) {
  FE2_CHECK(max_substep > 0.0, "max_substep {} must be > 0", max_substep);
  FE2_CHECK(p.r_s > 0.0 && p.r_s < 1.0 && p.r_w > 0.0 && p.r_w < 1.0, "r_s {}, r_w {} not in (0, 1)",
            p.r_s, p.r_w);
  k_wu_ = p.k_uw * (1.0 / p.r_w - 1.0) - p.k_ws;
  k_su_ = p.k_ws * p.r_w * (1.0 / p.r_s - 1.0);
  A_ = p.A_eff * p.r_s / ((1.0 - p.r_s) * p.r_w + p.r_s);
  c_w_ = p.phi * p.k_uw * (1.0 - p.r_w) / p.r_w;
  c_s_ = p.phi * p.k_ws * p.r_w * (1.0 - p.r_s) / p.r_s;
  k_b_ = p.k_u * std::pow(p.TRPN_50, p.n_tm) / ((1.0 - p.r_s) * (1.0 - p.r_w));
  FE2_CHECK(k_wu_ >= 0.0, "k_wu = k_uw (1/r_w - 1) - k_ws = {} < 0", k_wu_);
  FE2_CHECK(p.ca50_ref + p.beta_1 * 0.2 > 0.0, "Ca50 <= 0 at lambda = 1.2");
}

std::string Land2017::description() const {
  return fmt::format(
      "land2017 (Land et al. 2017, {} parameter set{}): T_ref = {} kPa, Ca50_ref = {} µM, "
      "n_tm = {}, k_u = {}/s, k_uw = {}/s, k_ws = {}/s; {}; RK4 substeps <= {} s",
      set_name_, overridden_.empty() ? "" : " with " + overridden_ + " overridden",
      1e-3 * p_.T_ref, p_.ca50_ref, p_.n_tm, p_.k_u, p_.k_uw, p_.k_ws, calcium_.description(),
      max_substep_);
}

void Land2017::rest_state(std::span<double> y) const {
  FE2_CHECK(static_cast<int>(y.size()) == kStates, "state size {}", y.size());
  // The exact equilibrium at diastolic calcium and λ = 1 (ζ = 0): CaTRPN from its own
  // balance, then B, XW, XS proportional to XU, which closes the fractions to 1.
  const double r = std::pow(calcium_.parameters().rest / p_.ca50_ref, p_.n_TRPN);
  const double ca_trpn = r / (1.0 + r);
  const double c_half = std::pow(ca_trpn, 0.5 * p_.n_tm);
  const double blocked = k_b_ * std::min(100.0, 1.0 / c_half) / (p_.k_u * c_half);  // B / XU
  const double weak = p_.k_uw / (k_wu_ + p_.k_ws);                                   // XW / XU
  const double strong = p_.k_ws * weak / k_su_;                                      // XS / XU
  const double xu = 1.0 / (1.0 + blocked + weak + strong);
  y[0] = ca_trpn;
  y[1] = blocked * xu;
  y[2] = strong * xu;
  y[3] = weak * xu;
  y[4] = 0.0;
  y[5] = 0.0;
}

template <class T>
void Land2017::rhs(double ca, const T& lambda, const T& lambda_dot,
                   const std::array<T, kStates>& y, std::array<T, kStates>& dy) const {
  using std::abs, std::max, std::min, std::pow;
  const T lambda_m = min(lambda, 1.2);
  const T ca50 = p_.ca50_ref + p_.beta_1 * (lambda_m - 1.0);
  const T ca_trpn = max(y[0], 0.0);
  const T& blocked = y[1];
  const T xs = max(y[2], 0.0), xw = max(y[3], 0.0);
  const T& zeta_s = y[4];
  const T& zeta_w = y[5];
  const T xu = 1.0 - blocked - xs - xw;

  dy[0] = p_.k_TRPN * (pow(ca / ca50, p_.n_TRPN) * (1.0 - ca_trpn) - ca_trpn);

  // CaTRPN^{n_tm/2}, and the unblocking factor min(100, CaTRPN^{-n_tm/2}).
  const T c_half = value_of(ca_trpn) > 0.0 ? pow(ca_trpn, 0.5 * p_.n_tm) : T(0.0);
  const T unblock = value_of(c_half) > 0.01 ? 1.0 / c_half : T(100.0);
  dy[1] = k_b_ * unblock * xu - p_.k_u * c_half * blocked;

  T gamma_su(0.0);
  if (value_of(zeta_s) > 0.0)
    gamma_su = p_.gamma_s * zeta_s;
  else if (value_of(zeta_s) < -1.0)
    gamma_su = p_.gamma_s * (-zeta_s - 1.0);
  const T gamma_wu = p_.gamma_w * abs(zeta_w);
  dy[2] = p_.k_ws * xw - k_su_ * xs - gamma_su * xs;
  dy[3] = p_.k_uw * xu - k_wu_ * xw - p_.k_ws * xw - gamma_wu * xw;
  dy[4] = A_ * lambda_dot - c_s_ * zeta_s;
  dy[5] = A_ * lambda_dot - c_w_ * zeta_w;
}

template <class T>
T Land2017::tension(const T& lambda, const std::array<T, kStates>& y) const {
  using std::max, std::min;
  const T lambda_m = min(lambda, 1.2);
  const T h = max(1.0 + p_.beta_0 * (lambda_m + min(lambda_m, 0.87) - 1.87), 0.0);
  const T xs = max(y[2], 0.0), xw = max(y[3], 0.0);
  return (p_.T_ref / p_.r_s) * h * ((y[4] + 1.0) * xs + y[5] * xw);
}

ActiveTension Land2017::advance(const CellStep& step, std::span<const double> committed,
                                std::span<double> current) const {
  std::array<Dual, kStates> y;
  for (int i = 0; i < kStates; ++i) y[i] = committed[i];
  if (step.dt > 0.0)
    integrate_rk4(step, calcium_, max_substep_, y,
                  [this](double, double ca, const Dual& lambda, const Dual& rate,
                         const std::array<Dual, kStates>& z, std::array<Dual, kStates>& dz) {
                    rhs(ca, lambda, rate, z, dz);
                  });
  for (int i = 0; i < kStates; ++i) current[i] = y[i].v;
  const Dual ta = tension(Dual(step.lambda, 1.0, 0.0), y);
  return {ta.v, ta.dl, ta.dr};
}

}  // namespace fe2
