#include "worker/SparseFactor.h"

#include "common/error.h"
#include "worker/cholmod_factor_io.h"
#include "worker/large_pages.h"
#include "worker/ordering_lock.h"

#include <suitesparse/cholmod.h>
#include <suitesparse/umfpack.h>

#include <cstring>
#include <vector>

namespace fe2 {

namespace {

/// CHOLMOD supernodal LLᵀ. K is stored full; CHOLMOD reads its upper triangle (stype 1).
class CholmodFactor final : public SparseFactor {
 public:
  CholmodFactor() {
    cholmod_start(&c_);
    c_.supernodal = CHOLMOD_SUPERNODAL;
    c_.final_ll = 1;
    c_.print = 0;
    c_.error_handler = nullptr;
  }
  ~CholmodFactor() override {
    if (X_) cholmod_free_dense(&X_, &c_);
    if (Y_) cholmod_free_dense(&Y_, &c_);
    if (E_) cholmod_free_dense(&E_, &c_);
    if (L_) cholmod_free_factor(&L_, &c_);
    cholmod_finish(&c_);
  }

  void factorize(const SparseMatrix& K) override {
    cholmod_sparse A = view(K);
    if (!L_) {
      const std::lock_guard<std::mutex> lock(ordering_mutex());
      L_ = cholmod_analyze(&A, &c_);
      check("cholmod_analyze");
    }
    ready_ = false;
    cholmod_factorize(&A, L_, &c_);
    if (c_.status == CHOLMOD_NOT_POSDEF)
      throw NumericalError(fmt::format(
          "CHOLMOD: unit matrix K is not positive definite (leading minor {} of {}); use "
          "factorization \"lu\" or \"auto\" for units that lose stability",
          L_->minor, K.rows()));
    check("cholmod_factorize");
    ready_ = true;
  }

  void solve(const double* B, double* X, int nrhs) override {
    FE2_CHECK(ready_, "solve before factorize");
    cholmod_dense b{};
    b.nrow = L_->n;
    b.ncol = nrhs;
    b.nzmax = L_->n * nrhs;
    b.d = L_->n;
    b.x = const_cast<double*>(B);
    b.xtype = CHOLMOD_REAL;
    b.dtype = CHOLMOD_DOUBLE;
    cholmod_solve2(CHOLMOD_A, L_, &b, nullptr, &X_, nullptr, &Y_, &E_, &c_);
    check("cholmod_solve2");
    std::memcpy(X, X_->x, sizeof(double) * L_->n * nrhs);
  }

  std::string name() const override { return "cholmod_llt"; }
  double factor_flops() const override { return c_.fl; }
  double solve_flops() const override { return 4.0 * c_.lnz; }
  double factor_bytes() const override {
    return L_ ? static_cast<double>(L_->xsize) * sizeof(double) : 0.0;
  }

  bool savable() const override { return true; }
  void save(ByteWriter& w) const override {
    FE2_CHECK(ready_, "save before factorize");
    write_cholmod_factor(w, *L_, {c_.fl, c_.lnz});
  }
  void load(ByteReader& r, const SparseMatrix& K) override {
    CholmodCounts counts;
    cholmod_factor* L = read_cholmod_factor(r, K, c_, counts);
    if (L_) cholmod_free_factor(&L_, &c_);
    L_ = L;
    c_.fl = counts.fl;  // as cholmod_analyze left them for this factor
    c_.lnz = counts.lnz;
    ready_ = true;
  }

 private:
  static cholmod_sparse view(const SparseMatrix& K) {
    cholmod_sparse A;
    cholmod_upper_view(K, A);
    return A;
  }
  void check(const char* what) const {
    if (c_.status < CHOLMOD_OK)
      throw NumericalError(fmt::format("CHOLMOD {} failed with status {}", what, c_.status));
  }

  cholmod_common c_;
  cholmod_factor* L_ = nullptr;
  cholmod_dense* X_ = nullptr;
  cholmod_dense* Y_ = nullptr;
  cholmod_dense* E_ = nullptr;
};

/// UMFPACK LU for unsymmetric K.
class UmfpackFactor final : public SparseFactor {
 public:
  UmfpackFactor() { umfpack_di_defaults(control_); }
  ~UmfpackFactor() override {
    if (numeric_) umfpack_di_free_numeric(&numeric_);
    if (symbolic_) umfpack_di_free_symbolic(&symbolic_);
  }

  void factorize(const SparseMatrix& K) override {
    const int n = static_cast<int>(K.rows());
    n_ = n;
    if (!symbolic_) {
      const std::lock_guard<std::mutex> lock(ordering_mutex());  // UMFPACK may order with METIS
      check(umfpack_di_symbolic(n, n, K.outerIndexPtr(), K.innerIndexPtr(), K.valuePtr(),
                                &symbolic_, control_, info_),
            "umfpack_di_symbolic");
      Wi_.resize(n);
      W_.resize(5 * static_cast<size_t>(n));
    }
    ready_ = false;
    if (numeric_) umfpack_di_free_numeric(&numeric_);
    const int status = umfpack_di_numeric(K.outerIndexPtr(), K.innerIndexPtr(), K.valuePtr(),
                                          symbolic_, &numeric_, control_, info_);
    if (status == UMFPACK_WARNING_singular_matrix)
      throw NumericalError("UMFPACK: unit matrix K is singular (status 1)");
    check(status, "umfpack_di_numeric");
    ready_ = true;
  }

  void solve(const double* B, double* X, int nrhs) override {
    FE2_CHECK(ready_, "solve before factorize");
    const int n = n_;
    double control[UMFPACK_CONTROL];
    std::memcpy(control, control_, sizeof(control));
    // No refinement: the factor is a preconditioner for a K that has moved on, so the
    // matrix arrays are not needed (and not passed) here.
    control[UMFPACK_IRSTEP] = 0;
    std::vector<double> x(n);
    for (int c = 0; c < nrhs; ++c) {
      check(umfpack_di_wsolve(UMFPACK_A, nullptr, nullptr, nullptr, x.data(), B + static_cast<size_t>(c) * n, numeric_,
                              control, info_, Wi_.data(), W_.data()),
            "umfpack_di_wsolve");
      std::memcpy(X + static_cast<size_t>(c) * n, x.data(), sizeof(double) * n);
    }
  }

  std::string name() const override { return "umfpack_lu"; }
  double factor_flops() const override { return info_[UMFPACK_FLOPS]; }
  double solve_flops() const override {
    return 2.0 * (info_[UMFPACK_LNZ] + info_[UMFPACK_UNZ]);
  }
  double factor_bytes() const override {
    return info_[UMFPACK_NUMERIC_SIZE] * info_[UMFPACK_SIZE_OF_UNIT];
  }

 private:
  static void check(int status, const char* what) {
    if (status != UMFPACK_OK)
      throw NumericalError(fmt::format("UMFPACK {} failed with status {}", what, status));
  }
  double control_[UMFPACK_CONTROL];
  double info_[UMFPACK_INFO] = {};
  void* symbolic_ = nullptr;
  void* numeric_ = nullptr;
  int n_ = 0;
  std::vector<int> Wi_;
  std::vector<double> W_;
};

}  // namespace

void SparseFactor::save(ByteWriter&) const {
  throw Error(fmt::format("{}: this factor cannot be saved (it is rebuilt from its matrix)", name()));
}

void SparseFactor::load(ByteReader&, const SparseMatrix&) {
  throw Error(fmt::format("{}: this factor cannot be loaded (it is rebuilt from its matrix)", name()));
}

std::unique_ptr<SparseFactor> make_sparse_factor(FactorKind kind) {
  use_large_pages_in_suitesparse();  // factors on 2 MiB pages (worker/large_pages.h)
  if (kind == FactorKind::cholesky) return std::make_unique<CholmodFactor>();
  return std::make_unique<UmfpackFactor>();
}

}  // namespace fe2
