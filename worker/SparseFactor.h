#pragma once
// A cached sparse factorization of the unit matrix K (paper Fig. 6, line c1), used as
// a direct solver right after a refresh and as the GMRES preconditioner until the
// next one. Two backends: CHOLMOD supernodal LLᵀ (K symmetric positive definite; the
// paper's choice even in systole) and UMFPACK LU (any K). Every library status is
// checked and reported with the library's own code.
#include <Eigen/Sparse>

#include <memory>
#include <string>

namespace fe2 {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

class SparseFactor {
 public:
  virtual ~SparseFactor() = default;
  /// Numeric factorization of K (symbolic analysis on the first call; the pattern of
  /// K must not change afterwards). Throws NumericalError if K is singular or, for
  /// LLᵀ, not positive definite.
  virtual void factorize(const SparseMatrix& K) = 0;
  /// X = K⁻¹ B for `nrhs` column-major right-hand sides of length n (B, X may alias).
  virtual void solve(const double* B, double* X, int nrhs) = 0;
  virtual std::string name() const = 0;
  /// Bytes held by the numeric factor (for traces and the memory budget).
  virtual double factor_bytes() const = 0;
  /// Floating-point operations of one factorization and of one solve, as the library
  /// counts them: a deterministic cost model for the adaptive refresh policy.
  virtual double factor_flops() const = 0;
  virtual double solve_flops() const = 0;
  bool ready() const { return ready_; }

 protected:
  bool ready_ = false;
};

enum class FactorKind { cholesky, lu };

std::unique_ptr<SparseFactor> make_sparse_factor(FactorKind kind);

}  // namespace fe2
