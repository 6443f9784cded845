#include "common/fem/quadrature.h"

#include "common/error.h"

#include <cmath>

namespace fe2 {

namespace {

/// Gauss–Legendre on [0, 1] with n points (Golub–Welsch would be overkill: Newton on P_n).
std::vector<std::pair<double, double>> gauss01(int n) {
  std::vector<std::pair<double, double>> out;
  for (int i = 1; i <= n; ++i) {
    double x = std::cos(M_PI * (i - 0.25) / (n + 0.5));
    double dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      const double pn = n == 0 ? 1.0 : (n == 1 ? x : p1);
      const double pm = n == 1 ? 1.0 : p0;
      dp = n * (x * pn - pm) / (x * x - 1.0);
      const double dx = pn / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    out.emplace_back(0.5 * (1.0 - x), 0.5 * w);  // mapped to [0, 1]
  }
  return out;
}

}  // namespace

std::vector<TetQuadraturePoint> tet_rule(int degree) {
  FE2_CHECK(degree >= 0, "quadrature degree {} < 0", degree);
  if (degree <= 1) return {{Vec4::Constant(0.25), 1.0 / 6.0}};
  if (degree == 2) {
    const double a = (5.0 + 3.0 * std::sqrt(5.0)) / 20.0, b = (5.0 - std::sqrt(5.0)) / 20.0;
    std::vector<TetQuadraturePoint> r;
    for (int k = 0; k < 4; ++k) {
      Vec4 l = Vec4::Constant(b);
      l[k] = a;
      r.push_back({l, 1.0 / 24.0});
    }
    return r;
  }
  // x = u(1−v)(1−w), y = v(1−w), z = w on [0,1]³, Jacobian (1−v)(1−w)².
  const int n = (degree + 3 + 1) / 2;
  const auto g = gauss01(n);
  std::vector<TetQuadraturePoint> r;
  for (const auto& [u, wu] : g)
    for (const auto& [v, wv] : g)
      for (const auto& [w, ww] : g) {
        const double x = u * (1 - v) * (1 - w), y = v * (1 - w), z = w;
        r.push_back({Vec4(1 - x - y - z, x, y, z), wu * wv * ww * (1 - v) * (1 - w) * (1 - w)});
      }
  return r;
}

std::vector<TriangleQuadraturePoint> triangle_rule(int degree) {
  FE2_CHECK(degree >= 0, "quadrature degree {} < 0", degree);
  if (degree <= 1) return {{Vec3::Constant(1.0 / 3.0), 0.5}};
  // x = u(1−v), y = v on [0,1]², Jacobian (1−v).
  const int n = (degree + 2 + 1) / 2;
  const auto g = gauss01(n);
  std::vector<TriangleQuadraturePoint> r;
  for (const auto& [u, wu] : g)
    for (const auto& [v, wv] : g) {
      const double x = u * (1 - v), y = v;
      r.push_back({Vec3(1 - x - y, x, y), wu * wv * (1 - v)});
    }
  return r;
}

}  // namespace fe2
