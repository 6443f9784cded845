#pragma once
// A test-only law with history: a neo-Hookean whose stiffness grows with an internal
// variable α that integrates a function of the rate over time (backward Euler),
//
//   α_{n+1} = α_n + Δt · k (1 + t) Ż:Ż,       Π = (1 + α_{n+1}) Π^NH(Z),
//
// so Π depends on t, Δt, Ż and the committed α_n. The tangent holds the context fixed,
// 𝔸 = (1 + α_{n+1}) 𝔸^NH (not consistent in Ż; enough for tests, and symmetric).
// Besides α the law records what it was given, so tests can read the context a point
// received from the point's history: [α, t, Δt, Ż(0..8)].
#include "common/materials/NeoHookean.h"

namespace fe2::test {

class HistoryLaw final : public Material {
 public:
  static constexpr int kAlpha = 0, kTime = 1, kDt = 2, kZdot = 3, kSize = 12;

  HistoryLaw(double E, double nu, double k) : nh_(E, nu), k_(k) {}
  std::string name() const override { return "test_history"; }
  double energy(const Vec9& Z) const override { return nh_.energy(Z); }
  /// Without a context: α = 0 (a point that has seen no rate).
  void stress_and_tangent(const Vec9& Z, Vec9& Pi, Mat9& A) const override {
    nh_.stress_and_tangent(Z, Pi, A);
  }
  int history_size() const override { return kSize; }
  void stress_and_tangent_at(const Vec9& Z, const MaterialPointContext& ctx, PointHistory h,
                             Vec9& Pi, Mat9& A, Mat9& A_rate) const override {
    A_rate.setZero();
    const double alpha = alpha_next(h.committed[kAlpha], ctx);
    nh_.stress_and_tangent(Z, Pi, A);
    Pi *= 1.0 + alpha;
    A *= 1.0 + alpha;
    h.current[kAlpha] = alpha;
    h.current[kTime] = ctx.time;
    h.current[kDt] = ctx.dt;
    for (int i = 0; i < 9; ++i) h.current[kZdot + i] = ctx.Zdot[i];
  }
  double stiffness_scale() const override { return nh_.stiffness_scale(); }

  /// α_{n+1} from α_n and the context (the formula above).
  double alpha_next(double alpha_n, const MaterialPointContext& ctx) const {
    return alpha_n + ctx.dt * k_ * (1.0 + ctx.time) * ctx.Zdot.squaredNorm();
  }

 private:
  NeoHookean nh_;
  double k_;
};

}  // namespace fe2::test
