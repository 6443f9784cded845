#pragma once
// Time integration of a cell model's state over one macro step [t_n, t_{n+1}]
// (CellModel::advance): ceil(Δt / max_substep) equal substeps of the classical
// 4th-order Runge–Kutta scheme; a substep that contains a calcium beat onset (where the
// template has a kink) is split there, so the scheme keeps its order through it.
//
// With T = Dual the stretch λ(s) = λ − (t_{n+1} − s) λ̇ and the rate λ̇ are seeded with
// their derivatives in λ and λ̇: RK4 applied to the state in Dual arithmetic *is* the
// derivative of the RK4 map (the forward sensitivities of the discrete update), so the
// T_a computed from the result carries exact dT_a/dλ and dT_a/dλ̇.
//
// Why explicit RK4 suffices: the stiffest rate of the models here is the tropomyosin
// unblocking of Land 2017 (k_b·100 + k_u ≈ 2.4 ms⁻¹ intact, ≈ 27 ms⁻¹ skinned), so
// |λ h| ≈ 0.24 (intact) or 2.7 (skinned, still inside RK4's stability interval ≈ 2.78)
// at the default 0.1 ms substep; accuracy, not stability, sets the substep.
#include "common/cellmodels/CalciumTransient.h"
#include "common/cellmodels/CellModel.h"
#include "common/cellmodels/Dual.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

namespace fe2 {

/// λ at time s inside the step, with its derivatives when T is Dual.
template <class T>
T stretch_at(const CellStep& step, double s) {
  const double back = step.time - s;
  if constexpr (std::is_same_v<T, Dual>)
    return Dual(step.lambda - back * step.lambda_dot, 1.0, -back);
  else
    return step.lambda - back * step.lambda_dot;
}

template <class T>
T stretch_rate(const CellStep& step) {
  if constexpr (std::is_same_v<T, Dual>)
    return Dual(step.lambda_dot, 0.0, 1.0);
  else
    return step.lambda_dot;
}

/// Substeps of at most `max_substep` over the step; `rhs(t, Ca(t), λ(t), λ̇, y, dy)`
/// writes dy/dt. Allocates nothing.
template <class T, std::size_t N, class Rhs>
void integrate_rk4(const CellStep& step, const CalciumTransient& calcium, double max_substep,
                   std::array<T, N>& y, const Rhs& rhs) {
  const double t0 = step.time - step.dt;
  const T rate = stretch_rate<T>(step);
  std::array<T, N> k1, k2, k3, k4, z;

  // One RK4 step over [a, b] with the calcium at a, the midpoint and b.
  auto rk4 = [&](double a, double b, double ca_a, double ca_m, double ca_b) {
    const double h = b - a, m = a + 0.5 * h;
    rhs(a, ca_a, stretch_at<T>(step, a), rate, y, k1);
    for (std::size_t i = 0; i < N; ++i) z[i] = y[i] + (0.5 * h) * k1[i];
    const T lambda_m = stretch_at<T>(step, m);
    rhs(m, ca_m, lambda_m, rate, z, k2);
    for (std::size_t i = 0; i < N; ++i) z[i] = y[i] + (0.5 * h) * k2[i];
    rhs(m, ca_m, lambda_m, rate, z, k3);
    for (std::size_t i = 0; i < N; ++i) z[i] = y[i] + h * k3[i];
    rhs(b, ca_b, stretch_at<T>(step, b), rate, z, k4);
    for (std::size_t i = 0; i < N; ++i)
      y[i] += (h / 6.0) * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
  };
  auto ca = [&](double t) { return calcium.value(t, step.activation_time); };

  // The (1 − 1e-12) keeps Δt = 10 max_substep at 10 substeps despite round-off.
  const int n = std::max(1, static_cast<int>(std::ceil(step.dt / max_substep * (1.0 - 1e-12))));
  const double h = step.dt / n;
  double a = t0, ca_a = ca(t0);
  for (int i = 0; i < n; ++i) {
    const double b = i + 1 == n ? step.time : t0 + (i + 1) * h;
    const double onset = calcium.next_onset(a, step.activation_time);
    const double eps = 1e-9 * h;
    if (onset > a + eps && onset < b - eps) {
      // Left of the onset the previous beat's tail, right of it rest (s = 0).
      rk4(a, onset, ca_a, ca(0.5 * (a + onset)), ca(onset));
      const double ca_b = ca(b);
      rk4(onset, b, calcium.parameters().rest, ca(0.5 * (onset + b)), ca_b);
      ca_a = ca_b;
    } else {
      const double ca_b = ca(b);
      rk4(a, b, ca_a, ca(0.5 * (a + b)), ca_b);
      ca_a = ca_b;
    }
    a = b;
  }
}

}  // namespace fe2
