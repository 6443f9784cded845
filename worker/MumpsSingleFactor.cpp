#include "worker/MumpsSingleFactor.h"

#include "common/error.h"
#include "common/linalg/mumps_count.h"
#include "common/linalg/nested_dissection.h"
#include "worker/ordering_lock.h"

#include <mpi.h>
#include <smumps_c.h>

#include <cmath>
#include <exception>
#include <mutex>
#include <vector>

namespace fe2 {

namespace {

// MUMPS documents its controls 1-based.
#define ICNTL(k) icntl[(k)-1]
#define CNTL(k) cntl[(k)-1]
#define INFOG(k) infog[(k)-1]
#define RINFOG(k) rinfog[(k)-1]

class MumpsSingleFactor final : public SparseFactor {
 public:
  MumpsSingleFactor(bool symmetric, double blr_tolerance)
      : symmetric_(symmetric), blr_tolerance_(blr_tolerance) {
    // One process per unit: the farm already spreads units over ranks.
    id_.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(MPI_COMM_SELF));
    id_.par = 1;
    // 1: LDLᵀ without pivoting, under the LLᵀ kind's contract (K symmetric positive
    // definite, as CHOLMOD assumes). Measured on the 27,780-DOF unit against SYM = 2
    // (general symmetric, with pivoting): 81.5 against 96.3 Gflop, refresh 1.29× against
    // 1.87× CHOLMOD's, 191 against 215 MB (docs/benchmarks/2026-11-micro-unit.md,
    // "Single-precision factor").
    id_.sym = symmetric ? 1 : 0;
    run(-1, "initialization");
    initialized_ = true;
    id_.ICNTL(1) = -1;  // silent: errors are reported from INFOG below
    id_.ICNTL(2) = -1;
    id_.ICNTL(3) = -1;
    id_.ICNTL(4) = 0;
    id_.ICNTL(5) = 0;   // assembled, centralized on the host
    id_.ICNTL(18) = 0;
    id_.ICNTL(14) = 50; // workspace margin for pivoting (percent)
    // METIS's nested dissection, as CHOLMOD uses, computed here and passed as the user's
    // order (ICNTL(7) = 1): MUMPS's automatic choice on one process measured ≈ 4×
    // CHOLMOD's flops on a 3k-DOF unit, and Debian's MUMPS has no METIS of its own (a
    // request for it, ICNTL(7) = 5, silently gives PORD).
    id_.ICNTL(7) = 1;
    if (blr_tolerance_ > 0) {
      id_.ICNTL(35) = 2;  // BLR in factorization and solve
      id_.CNTL(7) = static_cast<float>(blr_tolerance_);
    }
  }
  ~MumpsSingleFactor() override {
    if (!initialized_) return;
    id_.job = -2;
    smumps_c(&id_);
  }

  void factorize(const SparseMatrix& K) override {
    if (pos_.empty()) analyse(K);
    FE2_CHECK(K.nonZeros() == nnz_K_, "the pattern of K changed after the analysis");
    ready_ = false;
    const double* v = K.valuePtr();
    for (size_t k = 0; k < pos_.size(); ++k) a_[k] = static_cast<float>(v[pos_[k]]);
    id_.a = a_.data();
    run(2, "factorization");
    ready_ = true;
  }

  void solve(const double* B, double* X, int nrhs) override {
    FE2_CHECK(ready_, "solve before factorize");
    const size_t len = static_cast<size_t>(n_) * nrhs;
    rhs_.resize(len);
    for (size_t i = 0; i < len; ++i) rhs_[i] = static_cast<float>(B[i]);
    id_.rhs = rhs_.data();
    id_.nrhs = nrhs;
    id_.lrhs = n_;
    run(3, "solve");
    for (size_t i = 0; i < len; ++i) X[i] = rhs_[i];
  }

  std::string name() const override {
    return std::string(symmetric_ ? "mumps_single_ldlt" : "mumps_single_lu") +
           (blr_tolerance_ > 0 ? "_blr" : "");
  }
  /// RINFOG(3): operations of the elimination as performed (after BLR compression).
  double factor_flops() const override { return id_.RINFOG(3); }
  /// Forward and backward substitution over the factor's entries (INFOG(29), after
  /// compression); an LDLᵀ factor's entries are read twice.
  double solve_flops() const override {
    return (symmetric_ ? 4.0 : 2.0) * mumps_count(id_.INFOG(29));
  }
  /// INFOG(22): megabytes MUMPS used in the factorization, the factor included; MUMPS
  /// keeps that workspace until the instance ends.
  double factor_bytes() const override { return ready_ ? 1e6 * id_.INFOG(22) : 0.0; }

 private:
  void analyse(const SparseMatrix& K) {
    n_ = static_cast<int>(K.rows());
    nnz_K_ = K.nonZeros();
    for (int c = 0; c < K.outerSize(); ++c)
      for (int k = K.outerIndexPtr()[c]; k < K.outerIndexPtr()[c + 1]; ++k) {
        const int r = K.innerIndexPtr()[k];
        if (symmetric_ && r > c) continue;  // a symmetric MUMPS sums (i,j) and (j,i): pass one
        pos_.push_back(k);
        irn_.push_back(r + 1);  // 1-based
        jcn_.push_back(c + 1);
      }
    a_.assign(pos_.size(), 0.0f);
    {
      const std::lock_guard<std::mutex> lock(ordering_mutex());  // METIS draws from rand()
      perm_in_ = nested_dissection_positions(n_, irn_, jcn_, 1);
    }
    id_.perm_in = perm_in_.data();
    id_.n = n_;
    id_.nnz = static_cast<MUMPS_INT8>(pos_.size());
    id_.irn = irn_.data();
    id_.jcn = jcn_.data();
    id_.a = a_.data();
    run(1, "analysis");
    FE2_CHECK(id_.INFOG(7) == 1, "MUMPS analysed the unit matrix with ordering {}, not the one given",
              id_.INFOG(7));
  }

  void run(int job, const char* what) {
    id_.job = job;
    smumps_c(&id_);
    const int code = id_.INFOG(1);
    if (code >= 0) return;
    const std::string msg = fmt::format(
        "MUMPS single-precision {} of the unit matrix K ({} equations) failed: INFOG(1) = {}, "
        "INFOG(2) = {}",
        what, n_, code, id_.INFOG(2));
    // -10: numerically singular; -8/-9/-14/-15/-17/-20: workspace too small after
    // pivoting (the caller may cut the step); -13: allocation failed (no recovery).
    if (code == -13)
      throw Error(msg + " (out of memory: lower the unit resolution or use precision "
                        "\"double\")");
    if (code == -10) throw NumericalError(msg + " (K is singular in single precision)");
    throw NumericalError(msg);
  }

  const bool symmetric_;
  const double blr_tolerance_;
  SMUMPS_STRUC_C id_{};
  bool initialized_ = false;
  int n_ = 0;
  Eigen::Index nnz_K_ = 0;
  std::vector<int> pos_;  ///< position in K's value array of each entry passed
  std::vector<MUMPS_INT> irn_, jcn_;
  std::vector<int> perm_in_;  ///< the pivot order passed to the analysis (1-based)
  std::vector<float> a_, rhs_;
};

}  // namespace

std::unique_ptr<SparseFactor> make_mumps_single_factor(bool symmetric, double blr_tolerance) {
  return std::make_unique<MumpsSingleFactor>(symmetric, blr_tolerance);
}

}  // namespace fe2
