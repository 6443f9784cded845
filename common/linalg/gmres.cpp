#include "common/linalg/gmres.h"

#include <cmath>
#include <vector>

namespace fe2 {

namespace {

/// w = Σ y_j Az_j, when that stands for A x = A Σ y_j z_j as well as a product would:
/// its rounding is ≈ j·eps·Σ|y_j|‖Az_j‖ plus A times x's own, ≈ j·eps·Σ|y_j|‖z_j‖, within
/// a few eps of ‖w‖ and ‖x‖ unless the terms cancel. Where either sum cancels by more
/// than half (false returned), e.g. along directions A nearly annihilates, the caller
/// forms A x itself.
bool combine_products(const std::vector<Vec>& Az, const std::vector<Vec>& Z, const Vec& y,
                      const Vec& x, Vec& w) {
  w = y[0] * Az[0];
  double w_terms = std::abs(y[0]) * Az[0].norm(), x_terms = std::abs(y[0]) * Z[0].norm();
  for (Eigen::Index i = 1; i < y.size(); ++i) {
    w += y[i] * Az[i];
    w_terms += std::abs(y[i]) * Az[i].norm();
    x_terms += std::abs(y[i]) * Z[i].norm();
  }
  return w.norm() >= 0.5 * w_terms && x.norm() >= 0.5 * x_terms;
}

}  // namespace

GmresResult gmres(const LinearOp& A, const LinearOp& Minv, const Vec& b, Vec& x, double tol,
                  int restart, int max_iterations, const ResidualFloor& floor) {
  const Eigen::Index n = b.size();
  GmresResult res;
  Vec r(n), w(n);
  const bool from_zero = x.isZero(0.0);
  if (from_zero)  // the usual start: A·0 = 0 without an operator application
    w.setZero();
  else
    A(x, w);
  r = b - w;
  double beta = r.norm();
  res.residual = beta;
  const auto met = [&] { return beta <= tol || (floor && beta <= floor(x)); };
  if (met()) {
    res.converged = true;
    return res;
  }
  const int m = std::max(1, restart);
  // Krylov basis V and Z_j = M⁻¹ V_j (kept so the update needs no extra solve); both
  // grow only as far as the iteration goes, since a good preconditioner needs one or two.
  std::vector<Vec> V, Z;
  V.reserve(m + 1);
  Z.reserve(m);
  Eigen::MatrixXd Hm = Eigen::MatrixXd::Zero(m + 1, m);  // Hessenberg, Givens-rotated
  Vec cs(m), sn(m), g(m + 1);
  // A z_j of the first cycle from x = 0, kept before Gram–Schmidt overwrites them: if
  // that cycle ends within kKeptProducts iterations, x = Σ y_j z_j and A x = Σ y_j (A z_j)
  // to a few roundings per entry, so the true residual needs no further product. With a
  // fresh preconditioner that is every Step 1 solve (one or two iterations, by the
  // factor's precision): one operator application per iteration, none after.
  constexpr int kKeptProducts = 4;
  std::vector<Vec> Az;
  bool first_cycle = true;

  while (res.iterations < max_iterations) {
    if (V.empty()) V.emplace_back(n);
    V[0] = r / beta;
    g.setZero();
    g[0] = beta;
    int j = 0;
    for (; j < m && res.iterations < max_iterations; ++j) {
      if (static_cast<int>(Z.size()) <= j) Z.emplace_back(n);
      if (static_cast<int>(V.size()) <= j + 1) V.emplace_back(n);
      Minv(V[j], Z[j]);
      A(Z[j], w);
      if (first_cycle && from_zero && j < kKeptProducts) Az.push_back(w);
      ++res.iterations;
      // Modified Gram–Schmidt
      for (int i = 0; i <= j; ++i) {
        Hm(i, j) = w.dot(V[i]);
        w -= Hm(i, j) * V[i];
      }
      Hm(j + 1, j) = w.norm();
      if (Hm(j + 1, j) > 0) V[j + 1] = w / Hm(j + 1, j);
      for (int i = 0; i < j; ++i) {  // apply earlier rotations
        const double t = cs[i] * Hm(i, j) + sn[i] * Hm(i + 1, j);
        Hm(i + 1, j) = -sn[i] * Hm(i, j) + cs[i] * Hm(i + 1, j);
        Hm(i, j) = t;
      }
      const double d = std::hypot(Hm(j, j), Hm(j + 1, j));
      cs[j] = d > 0 ? Hm(j, j) / d : 1.0;
      sn[j] = d > 0 ? Hm(j + 1, j) / d : 0.0;
      Hm(j, j) = d;
      Hm(j + 1, j) = 0.0;
      g[j + 1] = -sn[j] * g[j];
      g[j] = cs[j] * g[j];
      if (std::abs(g[j + 1]) <= tol || Hm(j, j) == 0.0) {
        ++j;
        break;
      }
    }
    // x += M⁻¹ V y = Z y, with H y = g (upper triangular j x j)
    const Vec y = Hm.topLeftCorner(j, j).triangularView<Eigen::Upper>().solve(g.head(j));
    for (int i = 0; i < j; ++i) x += y[i] * Z[i];
    if (!(first_cycle && from_zero && j >= 1 && j <= kKeptProducts &&
          combine_products(Az, Z, y, x, w)))
      A(x, w);
    first_cycle = false;
    Az = {};
    r = b - w;
    beta = r.norm();
    res.residual = beta;
    if (!std::isfinite(beta)) return res;
    if (met()) {
      res.converged = true;
      return res;
    }
  }
  return res;
}

}  // namespace fe2
