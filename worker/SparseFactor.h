#pragma once
// A cached sparse factorization of the unit matrix K (paper Fig. 6, line c1), used as
// a direct solver right after a refresh and as the GMRES preconditioner until the
// next one. Two backends: CHOLMOD supernodal LLᵀ (K symmetric positive definite; the
// paper's choice even in systole) and UMFPACK LU (any K). Every library status is
// checked and reported with the library's own code.
#include "common/bytes.h"

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
  /// Ends a refresh: what is kept between jobs in lower precision than it was factored
  /// in (a float factor kept in binary16) is rounded here, after the refresh's own
  /// solves (χ) had the factor at full accuracy. Solves work before and after.
  virtual void compact() {}
  /// Bytes held by the numeric factor (for traces and the memory budget).
  virtual double factor_bytes() const = 0;
  /// Floating-point operations of one factorization and of one solve, as the library
  /// counts them: a deterministic cost model for the adaptive refresh policy.
  virtual double factor_flops() const = 0;
  virtual double solve_flops() const = 0;
  bool ready() const { return ready_; }

  /// Checkpoints that carry factors (output.checkpoint_factors): whether this backend can
  /// write its numeric factor out and read it back (CHOLMOD LLᵀ; not UMFPACK's opaque
  /// Numeric object nor MUMPS, whose owners rebuild them from K instead).
  virtual bool savable() const { return false; }
  /// Writes the factor (ready() and savable() only).
  virtual void save(ByteWriter& w) const;
  /// Reads a factor save() wrote, of a matrix with K's pattern, in place of factorizing.
  /// Every field is checked against n and K's pattern before use: a damaged record is an
  /// fe2::Error, never a crash. Afterwards factor_flops/solve_flops are those of the
  /// saved factor's analysis, so a cost model reading them sees no difference.
  virtual void load(ByteReader& r, const SparseMatrix& K);

 protected:
  bool ready_ = false;
};

enum class FactorKind { cholesky, lu };

std::unique_ptr<SparseFactor> make_sparse_factor(FactorKind kind);

}  // namespace fe2
