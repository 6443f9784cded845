#pragma once
// A forward-mode dual number carrying the two derivatives a cell model's step needs:
// ∂/∂λ and ∂/∂λ̇ (CellModel.h). Integrating a model's ODE in Dual arithmetic propagates
// the forward sensitivities through every stage and substep, so the derivatives are
// those of the computed (discrete) T_a, branch by branch. No heap, trivially copyable.
#include <cmath>

namespace fe2 {

struct Dual {
  double v = 0.0;   ///< value
  double dl = 0.0;  ///< ∂v/∂λ
  double dr = 0.0;  ///< ∂v/∂λ̇

  constexpr Dual() = default;
  constexpr Dual(double value) : v(value) {}  // NOLINT: constants promote implicitly
  constexpr Dual(double value, double d_lambda, double d_rate)
      : v(value), dl(d_lambda), dr(d_rate) {}

  Dual& operator+=(const Dual& b) { v += b.v; dl += b.dl; dr += b.dr; return *this; }
  Dual& operator-=(const Dual& b) { v -= b.v; dl -= b.dl; dr -= b.dr; return *this; }
};

inline Dual operator+(Dual a, const Dual& b) { return a += b; }
inline Dual operator-(Dual a, const Dual& b) { return a -= b; }
inline Dual operator-(const Dual& a) { return {-a.v, -a.dl, -a.dr}; }
inline Dual operator*(const Dual& a, const Dual& b) {
  return {a.v * b.v, a.dl * b.v + a.v * b.dl, a.dr * b.v + a.v * b.dr};
}
inline Dual operator*(double a, const Dual& b) { return {a * b.v, a * b.dl, a * b.dr}; }
inline Dual operator*(const Dual& a, double b) { return b * a; }
inline Dual operator/(const Dual& a, const Dual& b) {
  const double q = a.v / b.v;
  return {q, (a.dl - q * b.dl) / b.v, (a.dr - q * b.dr) / b.v};
}
inline Dual operator/(const Dual& a, double b) { return {a.v / b, a.dl / b, a.dr / b}; }
inline Dual operator/(double a, const Dual& b) {
  const double q = a / b.v;
  return {q, -q * b.dl / b.v, -q * b.dr / b.v};
}

inline double value_of(double x) { return x; }
inline double value_of(const Dual& x) { return x.v; }

/// x^p for x > 0 (callers clamp first); p constant.
inline Dual pow(const Dual& x, double p) {
  const double y = std::pow(x.v, p);
  const double dy = p * y / x.v;
  return {y, dy * x.dl, dy * x.dr};
}

/// The branch taken decides the derivative, as it decides the value.
inline Dual max(const Dual& a, double b) { return a.v > b ? a : Dual(b); }
inline Dual min(const Dual& a, double b) { return a.v < b ? a : Dual(b); }
inline Dual abs(const Dual& a) { return a.v < 0.0 ? -a : a; }

}  // namespace fe2
