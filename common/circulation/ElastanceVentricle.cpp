#include "common/circulation/ElastanceVentricle.h"

#include "common/error.h"

#include <Eigen/Dense>
#include <spdlog/fmt/fmt.h>

#include <cmath>
#include <limits>

namespace fe2 {

CavityFlows couple_step(const Circulation& circulation,
                        const std::vector<ElastanceVentricle>& ventricles, double t_new, double dt,
                        std::span<const double> committed, std::span<double> current,
                        std::vector<double>& p, std::vector<double>& V, int* iterations) {
  const int n = circulation.cavities();
  FE2_CHECK(static_cast<int>(ventricles.size()) == n && static_cast<int>(p.size()) == n &&
                static_cast<int>(V.size()) == n,
            "couple_step: {} ventricles, {} pressures, {} volumes for {} cavities",
            ventricles.size(), p.size(), V.size(), n);
  constexpr int kMaxIterations = 50;
  double previous = std::numeric_limits<double>::infinity();
  Eigen::VectorXd F(n);
  Eigen::MatrixXd J(n, n);
  for (int it = 0;; ++it) {
    const CavityFlows f = circulation.step(t_new, dt, p, committed, current);
    double scale = 1.0, norm = 0.0;
    int worst = 0;
    for (int c = 0; c < n; ++c) {
      const double E = ventricles[c].elastance(t_new);
      const double V_new = V[c] + dt * f.Q_net[c];
      F[c] = p[c] - E * (V_new - ventricles[c].V0());
      scale = std::max(scale, std::abs(p[c]) + E * std::abs(V_new));
      if (std::abs(F[c]) > norm) norm = std::abs(F[c]), worst = c;
      for (int j = 0; j < n; ++j) J(c, j) = (c == j ? 1.0 : 0.0) - E * dt * f.dQ(c, j);
    }
    if (!std::isfinite(norm))
      throw NumericalError(fmt::format("elastance ventricle '{}': non-finite pressure residual at t = {} s",
                                       circulation.cavity_names()[worst], t_new));
    if (norm <= 1e-14 * scale || (norm <= 1e-9 * scale && norm > 0.25 * previous)) {
      for (int c = 0; c < n; ++c) V[c] += dt * f.Q_net[c];
      if (iterations) *iterations = it;
      return f;
    }
    if (it == kMaxIterations)
      throw NumericalError(fmt::format(
          "elastance ventricle '{}': the pressure did not converge in {} Newton iterations at "
          "t = {} s (residual {:.3e} Pa)",
          circulation.cavity_names()[worst], kMaxIterations, t_new, norm));
    previous = norm;
    const Eigen::VectorXd dp = J.partialPivLu().solve(-F);
    for (int c = 0; c < n; ++c) p[c] += dp[c];
  }
}

}  // namespace fe2
