#include "worker/gmres.h"

#include <cmath>
#include <vector>

namespace fe2 {

GmresResult gmres(const LinearOp& A, const LinearOp& Minv, const Vec& b, Vec& x, double tol,
                  int restart, int max_iterations) {
  const Eigen::Index n = b.size();
  GmresResult res;
  Vec r(n), w(n), z(n);
  A(x, w);
  r = b - w;
  double beta = r.norm();
  res.residual = beta;
  if (beta <= tol) {
    res.converged = true;
    return res;
  }
  const int m = std::max(1, restart);
  std::vector<Vec> V(m + 1, Vec(n));
  Eigen::MatrixXd Hm = Eigen::MatrixXd::Zero(m + 1, m);  // Hessenberg, Givens-rotated
  Vec cs(m), sn(m), g(m + 1);

  while (res.iterations < max_iterations) {
    V[0] = r / beta;
    g.setZero();
    g[0] = beta;
    int j = 0;
    for (; j < m && res.iterations < max_iterations; ++j) {
      Minv(V[j], z);
      A(z, w);
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
    // x += M⁻¹ V y, with H y = g (upper triangular j x j)
    const Vec y = Hm.topLeftCorner(j, j).triangularView<Eigen::Upper>().solve(g.head(j));
    w.setZero();
    for (int i = 0; i < j; ++i) w += y[i] * V[i];
    Minv(w, z);
    x += z;
    A(x, w);
    r = b - w;
    beta = r.norm();
    res.residual = beta;
    if (!std::isfinite(beta)) return res;
    if (beta <= tol) {
      res.converged = true;
      return res;
    }
  }
  return res;
}

}  // namespace fe2
