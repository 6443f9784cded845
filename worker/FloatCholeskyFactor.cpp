#include "worker/FloatCholeskyFactor.h"

#include "common/error.h"
#include "worker/binary16_columns.h"
#include "worker/cholmod_factor_io.h"
#include "worker/large_pages.h"
#include "worker/ordering_lock.h"

#include <suitesparse/cholmod.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <vector>

// Single-precision BLAS/LAPACK (the Fortran interface every Debian BLAS provides).
extern "C" {
void ssyrk_(const char* uplo, const char* trans, const int* n, const int* k, const float* alpha,
            const float* a, const int* lda, const float* beta, float* c, const int* ldc);
void sgemm_(const char* ta, const char* tb, const int* m, const int* n, const int* k,
            const float* alpha, const float* a, const int* lda, const float* b, const int* ldb,
            const float* beta, float* c, const int* ldc);
void strsm_(const char* side, const char* uplo, const char* transa, const char* diag,
            const int* m, const int* n, const float* alpha, const float* a, const int* lda,
            float* b, const int* ldb);
void strsv_(const char* uplo, const char* trans, const char* diag, const int* n,
            const float* a, const int* lda, float* x, const int* incx);
void sgemv_(const char* trans, const int* m, const int* n, const float* alpha, const float* a,
            const int* lda, const float* x, const int* incx, const float* beta, float* y,
            const int* incy);
void spotrf_(const char* uplo, const int* n, float* a, const int* lda, int* info);
}

namespace fe2 {

namespace {

constexpr float kOne = 1.0f, kZero = 0.0f, kMinusOne = -1.0f;
constexpr int kInc = 1;

/// Factor values on large pages when they are big (the factor is streamed by every solve).
template <class T>
struct FactorArray {
  T* data = nullptr;
  size_t size = 0;
  FactorArray() = default;
  FactorArray(const FactorArray&) = delete;
  FactorArray& operator=(const FactorArray&) = delete;
  ~FactorArray() { release(); }
  void allocate(size_t n) {
    release();
    data = static_cast<T*>(large_page_alloc(n * sizeof(T)));
    if (!data && n > 0)
      throw Error(fmt::format("out of memory for a {}-byte-precision factor of {} entries "
                              "({:.0f} MB)", sizeof(T), n, 1e-6 * sizeof(T) * static_cast<double>(n)));
    size = n;
  }
  void release() {
    std::free(data);
    data = nullptr;
    size = 0;
  }
};
using FloatArray = FactorArray<float>;
// IEEE binary16: 11 significant bits, range ±65504. L of the unit-diagonal S K S has
// |L_ij| ≤ 1 (each row of L has unit norm), so nothing overflows; entries below 6e-5
// lose relative precision and those below 6e-8 vanish, which a preconditioner can afford.
using HalfArray = FactorArray<uint16_t>;

class FloatCholeskyFactor final : public SparseFactor {
 public:
  explicit FloatCholeskyFactor(bool half_storage) : half_storage_(half_storage) {
    cholmod_start(&c_);
    c_.supernodal = CHOLMOD_SUPERNODAL;  // the analysis builds supernodes and their rows
    c_.print = 0;
    c_.error_handler = nullptr;
  }
  ~FloatCholeskyFactor() override {
    if (L_) cholmod_free_factor(&L_, &c_);
    cholmod_finish(&c_);
  }

  void factorize(const SparseMatrix& K) override {
    if (!L_) {
      try {
        analyse(K);
      } catch (...) {  // leave no half-built analysis behind for a later call
        cholmod_free_factor(&L_, &c_);
        throw;
      }
    }
    FE2_CHECK(K.nonZeros() == nnz_K_ && K.rows() == n_,
              "the pattern of K changed after the analysis");
    ready_ = false;
    if (half_storage_) {  // the float values live only while refreshing (compact())
      Lh_.release();
      if (!Lx_.data) Lx_.allocate(static_cast<size_t>(L_->xsize));
    }
    load_scaled(K);
    numeric();
    ready_ = true;
  }

  /// binary16 storage: the float values are rounded and freed only now, so a refresh's
  /// χ solves use the float factor (half's 5e-4 rounding cost them extra refinement
  /// rounds and GMRES iterations: a refresh 1.1–1.7× CHOLMOD's double one).
  void compact() override {
    if (half_storage_ && Lx_.data) keep_in_half();
  }

  void solve(const double* B, double* X, int nrhs) override;

  std::string name() const override {
    return half_storage_ ? "supernodal_single_llt_half_storage" : "supernodal_single_llt";
  }
  double factor_flops() const override { return fl_; }
  double solve_flops() const override { return 4.0 * lnz_; }
  double factor_bytes() const override {
    return ready_ ? static_cast<double>(Lx_.size) * sizeof(float) +
                        static_cast<double>(Lh_.size) * sizeof(uint16_t) +
                        static_cast<double>(dest_.size()) * sizeof(int) +
                        static_cast<double>(L_->ssize) * sizeof(int)
                  : 0.0;
  }

 private:
  void analyse(const SparseMatrix& K);
  void load_scaled(const SparseMatrix& K);
  void numeric();
  /// Rounds the float factor to binary16 (packed) and frees the float values.
  void keep_in_half();
  /// Supernode s of the binary16 factor: its first column k1, nscol columns of nsrow
  /// rows, the row indices under its own columns; packed, column c holding rows c to
  /// nsrow − 1 only.
  struct HalfSupernode {
    int k1, nscol, nsrow;
    const int* below;
    const uint16_t* L;
    size_t column_start(int c) const {
      return static_cast<size_t>(c) * nsrow - static_cast<size_t>(c) * (c - 1) / 2;
    }
    /// L(c, c), L(c + 1, c), … of the supernode's column c.
    const uint16_t* column(int c) const { return L + column_start(c); }
  };
  HalfSupernode half_supernode(int s) const;
  /// The forward (L y = b) and backward (Lᵀ x = y) steps of supernode s on one
  /// right-hand side y, reading the binary16 values directly (binary16_columns.h);
  /// w holds the supernode's rows of y while it is worked on.
  void forward_half(int s, float* y, float* w) const;
  void backward_half(int s, float* y, float* w) const;
  /// L Lᵀ Y = Y in place (nrhs columns of n_), from Lx_ or from Lh_.
  void substitute_float(float* Y, int nrhs);
  void substitute_half(float* Y, int nrhs);

  int nsuper() const { return static_cast<int>(L_->nsuper); }
  const int* super() const { return static_cast<const int*>(L_->super); }
  const int* pi() const { return static_cast<const int*>(L_->pi); }
  const int* px() const { return static_cast<const int*>(L_->px); }
  const int* rows() const { return static_cast<const int*>(L_->s); }
  const int* perm() const { return static_cast<const int*>(L_->Perm); }

  cholmod_common c_;
  cholmod_factor* L_ = nullptr;  ///< symbolic only: supernodes, row patterns, Perm
  int n_ = 0;
  Eigen::Index nnz_K_ = 0;
  double fl_ = 0.0, lnz_ = 0.0;
  int max_rows_ = 0;              ///< rows of the tallest supernode
  std::vector<int> supernode_of_; ///< supernode holding each (permuted) column
  std::vector<int> dest_;         ///< Lx position of each upper entry of K, in K's order
  std::vector<double> scale_;     ///< S = diag(K)^(-1/2), original numbering
  bool half_storage_ = false;
  FloatArray Lx_;                 ///< the numeric factor, supernode by supernode
  HalfArray Lh_;                  ///< the same kept in binary16 (half_storage_; Lx_ released)
  std::vector<size_t> half_start_; ///< where each supernode starts in Lh_ (packed)
  // Workspace of the numeric factorization and the solves.
  std::vector<int> head_, next_, lpos_, map_, relative_map_;
  std::vector<float> update_, y_, e_;
  std::vector<double> column_scale_;
};

void FloatCholeskyFactor::analyse(const SparseMatrix& K) {
  n_ = static_cast<int>(K.rows());
  nnz_K_ = K.nonZeros();
  cholmod_sparse A;
  cholmod_upper_view(K, A);
  {
    const std::lock_guard<std::mutex> lock(ordering_mutex());
    L_ = cholmod_analyze(&A, &c_);
  }
  if (!L_ || c_.status < CHOLMOD_OK)
    throw NumericalError(fmt::format("CHOLMOD cholmod_analyze failed with status {}", c_.status));
  FE2_CHECK(L_->is_super, "CHOLMOD returned a simplicial analysis");
  fl_ = c_.fl;
  lnz_ = c_.lnz;

  const int ns = nsuper();
  supernode_of_.assign(n_, 0);
  for (int s = 0; s < ns; ++s) {
    for (int k = super()[s]; k < super()[s + 1]; ++k) supernode_of_[k] = s;
    max_rows_ = std::max(max_rows_, pi()[s + 1] - pi()[s]);
  }
  std::vector<int> pinv(n_);
  for (int k = 0; k < n_; ++k) pinv[perm()[k]] = k;

  // Where each upper entry K(i, j), i ≤ j, lands in L: column min(p(i), p(j)) and row
  // max(...) of the permuted matrix, inside that column's supernode. Entries are bucketed
  // by permuted column first so that one row map per supernode serves all of them.
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  std::vector<int> count(n_ + 1, 0);
  std::vector<int> entry_col, entry_row;
  for (int j = 0; j < n_; ++j)
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      const int i = inner[k];
      if (i > j) continue;
      const int pc = std::min(pinv[i], pinv[j]), pr = std::max(pinv[i], pinv[j]);
      entry_col.push_back(pc);
      entry_row.push_back(pr);
      ++count[pc + 1];
    }
  for (int c = 0; c < n_; ++c) count[c + 1] += count[c];
  std::vector<int> by_col(entry_col.size());
  {
    std::vector<int> fill(count.begin(), count.end() - 1);
    for (size_t e = 0; e < entry_col.size(); ++e) by_col[fill[entry_col[e]]++] = static_cast<int>(e);
  }
  dest_.assign(entry_col.size(), -1);
  map_.assign(n_, -1);
  for (int s = 0; s < ns; ++s) {
    const int k1 = super()[s], k2 = super()[s + 1];
    const int nsrow = pi()[s + 1] - pi()[s];
    for (int p = pi()[s]; p < pi()[s + 1]; ++p) map_[rows()[p]] = p - pi()[s];
    for (int c = k1; c < k2; ++c)
      for (int q = count[c]; q < count[c + 1]; ++q) {
        const int e = by_col[q];
        const int local = map_[entry_row[e]];
        FE2_CHECK(local >= 0 && local < nsrow && rows()[pi()[s] + local] == entry_row[e],
                  "K has an entry outside the pattern of its analysis");
        dest_[e] = px()[s] + (c - k1) * nsrow + local;
      }
  }
  Lx_.allocate(L_->xsize);
  head_.resize(ns);
  next_.resize(ns);
  lpos_.resize(ns);
  relative_map_.resize(max_rows_);
  update_.resize(std::max<size_t>(L_->maxcsize, 1));
  scale_.resize(n_);
}

// K̃ = S K S rounded to float, written straight into the factor's storage.
void FloatCholeskyFactor::load_scaled(const SparseMatrix& K) {
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  const double* v = K.valuePtr();
  size_t upper = 0;
  for (int j = 0; j < n_; ++j) {
    double d = 0.0;
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      if (!std::isfinite(v[k]))  // LAPACK's spotrf would pass a NaN on silently
        throw NumericalError(fmt::format("single-precision LLᵀ: unit matrix K has entry ({}, {}) = {}",
                                         inner[k], j, v[k]));
      if (inner[k] == j) d = v[k];
      if (inner[k] <= j) ++upper;
    }
    if (!(d > 0.0))
      throw NumericalError(fmt::format(
          "single-precision LLᵀ: unit matrix K has diagonal entry {} = {} (not positive "
          "definite); use factorization \"lu\" or \"auto\"", j, d));
    scale_[j] = 1.0 / std::sqrt(d);
  }
  FE2_CHECK(upper == dest_.size(), "the pattern of K changed after the analysis");
  std::fill(Lx_.data, Lx_.data + Lx_.size, 0.0f);
  size_t e = 0;
  for (int j = 0; j < n_; ++j)
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      const int i = inner[k];
      if (i > j) continue;
      Lx_.data[dest_[e++]] = static_cast<float>(v[k] * scale_[i] * scale_[j]);
    }
}

// Left-looking supernodal LLᵀ (the order of CHOLMOD's cholmod_super_numeric): supernode
// s gathers the updates of every descendant d whose rows reach s's columns,
//   L_s ← A_s − Σ_d L_d(rows ≥ k1) L_d(rows in [k1, k2))ᵀ,
// then factors its diagonal block (spotrf) and solves its off-diagonal rows (strsm).
// Each descendant waits in the linked list of the next supernode its rows reach.
void FloatCholeskyFactor::numeric() {
  const int ns = nsuper();
  const int* Super = super();
  const int* Lpi = pi();
  const int* Lpx = px();
  const int* Ls = rows();
  float* Lx = Lx_.data;
  std::fill(head_.begin(), head_.end(), -1);
  for (int s = 0; s < ns; ++s) {
    const int k1 = Super[s], k2 = Super[s + 1], nscol = k2 - k1;
    const int psi = Lpi[s], nsrow = Lpi[s + 1] - psi;
    float* Lsx = Lx + Lpx[s];
    for (int p = 0; p < nsrow; ++p) map_[Ls[psi + p]] = p;

    for (int d = head_[s]; d != -1;) {
      const int dnext = next_[d];
      const int ndcol = Super[d + 1] - Super[d];
      const int pdi = Lpi[d], pdend = Lpi[d + 1], ndrow = pdend - pdi;
      const int pdi1 = pdi + lpos_[d];
      int pdi2 = pdi1;
      while (pdi2 < pdend && Ls[pdi2] < k2) ++pdi2;
      const int ndrow1 = pdi2 - pdi1, ndrow2 = pdend - pdi1, ndrow3 = ndrow2 - ndrow1;
      const float* Ld = Lx + Lpx[d] + (pdi1 - pdi);
      if (update_.size() < static_cast<size_t>(ndrow2) * ndrow1)
        update_.resize(static_cast<size_t>(ndrow2) * ndrow1);
      float* C = update_.data();
      // C = L_d(rows ≥ k1) · L_d(rows in [k1, k2))ᵀ: its top square is symmetric.
      ssyrk_("L", "N", &ndrow1, &ndcol, &kOne, Ld, &ndrow, &kZero, C, &ndrow2);
      if (ndrow3 > 0)
        sgemm_("N", "T", &ndrow3, &ndrow1, &ndcol, &kOne, Ld + ndrow1, &ndrow, Ld, &ndrow, &kZero,
               C + ndrow1, &ndrow2);
      for (int i = 0; i < ndrow2; ++i) relative_map_[i] = map_[Ls[pdi1 + i]];
      for (int j = 0; j < ndrow1; ++j) {
        float* column = Lsx + static_cast<size_t>(relative_map_[j]) * nsrow;
        const float* c = C + static_cast<size_t>(j) * ndrow2;
        for (int i = j; i < ndrow2; ++i) column[relative_map_[i]] -= c[i];
      }
      lpos_[d] = pdi2 - pdi;
      if (pdi2 < pdend) {  // d's next rows belong to a later supernode
        const int next_s = supernode_of_[Ls[pdi2]];
        next_[d] = head_[next_s];
        head_[next_s] = d;
      }
      d = dnext;
    }

    int info = 0;
    spotrf_("L", &nscol, Lsx, &nsrow, &info);
    if (info != 0)
      throw NumericalError(fmt::format(
          "single-precision LLᵀ: unit matrix K is not positive definite in float (leading "
          "minor {} of {} in the fill-reducing order, at DOF {}); use precision \"double\" "
          "or factorization \"lu\"",
          k1 + info, n_, perm()[k1 + info - 1]));
    if (nsrow > nscol) {
      const int m = nsrow - nscol;
      strsm_("R", "L", "T", "N", &m, &nscol, &kOne, Lsx, &nsrow, Lsx + nscol, &nsrow);
      lpos_[s] = nscol;
      const int parent = supernode_of_[Ls[psi + nscol]];
      next_[s] = head_[parent];
      head_[parent] = s;
    }
  }
}

// Only the lower trapezoid of each supernode is kept: CHOLMOD's nscol × nsrow blocks
// also hold the strictly upper triangle of the diagonal block, unread by any solve
// (a quarter of the entries at ≈ 26k DOF).
void FloatCholeskyFactor::keep_in_half() {
  const int ns = nsuper();
  half_start_.assign(ns + 1, 0);
  for (int s = 0; s < ns; ++s) {
    const HalfSupernode h = half_supernode(s);
    half_start_[s + 1] = half_start_[s] + h.column_start(h.nscol);  // past its last column
  }
  Lh_.allocate(half_start_[ns]);
  for (int s = 0; s < ns; ++s) {
    const HalfSupernode h = half_supernode(s);
    for (int c = 0; c < h.nscol; ++c)
      floats_to_half(Lx_.data + px()[s] + static_cast<size_t>(c) * h.nsrow + c,
                     Lh_.data + half_start_[s] + h.column_start(c), h.nsrow - c);
  }
  Lx_.release();
}

FloatCholeskyFactor::HalfSupernode FloatCholeskyFactor::half_supernode(int s) const {
  HalfSupernode h;
  h.k1 = super()[s];
  h.nscol = super()[s + 1] - h.k1;
  h.nsrow = pi()[s + 1] - pi()[s];
  h.below = rows() + pi()[s] + h.nscol;
  h.L = Lh_.data ? Lh_.data + half_start_[s] : nullptr;
  return h;
}

// Forward: w = (y of the supernode's columns, 0 for its rows below). Blocks of
// kMaxHalfColumns columns: the block's triangle L_bb x_b = w_b, then every row under the
// block takes w −= L_·b x_b in one pass over the block's columns; the rows below the
// supernode then receive what they gathered.
void FloatCholeskyFactor::forward_half(int s, float* y, float* w) const {
  const HalfSupernode h = half_supernode(s);
  const int k1 = h.k1, nscol = h.nscol, nsrow = h.nsrow;
  std::copy(y + k1, y + k1 + nscol, w);
  std::fill(w + nscol, w + nsrow, 0.0f);
  const uint16_t* col[kMaxHalfColumns];
  for (int j0 = 0; j0 < nscol; j0 += kMaxHalfColumns) {
    const int b = std::min(kMaxHalfColumns, nscol - j0);
    for (int c = 0; c < b; ++c) {
      col[c] = h.column(j0 + c);  // from L(j0 + c, j0 + c) down
      w[j0 + c] /= half_to_float(col[c][0]);
      for (int r = c + 1; r < b; ++r) w[j0 + r] -= half_to_float(col[c][r - c]) * w[j0 + c];
      col[c] += b - c;  // from row j0 + b down
    }
    subtract_half_columns(b, nsrow - j0 - b, col, w + j0, w + j0 + b);
  }
  std::copy(w, w + nscol, y + k1);
  for (int i = 0; i < nsrow - nscol; ++i) y[h.below[i]] += w[nscol + i];
}

// Backward, last block first: x_b = L_bbᵀ⁻¹ (w_b − L_·bᵀ w_below), the dot products with
// every row under the block taken in one pass over its columns.
void FloatCholeskyFactor::backward_half(int s, float* y, float* w) const {
  const HalfSupernode h = half_supernode(s);
  const int k1 = h.k1, nscol = h.nscol, nsrow = h.nsrow;
  std::copy(y + k1, y + k1 + nscol, w);
  for (int i = 0; i < nsrow - nscol; ++i) w[nscol + i] = y[h.below[i]];
  const uint16_t* below_block[kMaxHalfColumns];
  for (int j0 = (nscol - 1) / kMaxHalfColumns * kMaxHalfColumns; j0 >= 0; j0 -= kMaxHalfColumns) {
    const int b = std::min(kMaxHalfColumns, nscol - j0);
    for (int c = 0; c < b; ++c) below_block[c] = h.column(j0 + c) + (b - c);
    float d[kMaxHalfColumns];
    dot_half_columns(b, nsrow - j0 - b, below_block, w + j0 + b, d);
    for (int c = b - 1; c >= 0; --c) {
      const uint16_t* Lc = h.column(j0 + c);
      float t = w[j0 + c] - d[c];
      for (int r = c + 1; r < b; ++r) t -= half_to_float(Lc[r - c]) * w[j0 + r];
      w[j0 + c] = t / half_to_float(Lc[0]);
    }
  }
  std::copy(w, w + nscol, y + k1);
}

// L Lᵀ y = y in place, from the float values: forward over the supernodes (diagonal
// triangle, then the rows below receive −L₂₁ x₁), backward in reverse.
void FloatCholeskyFactor::substitute_float(float* Y, int nrhs) {
  const int n = n_;
  const int* Super = super();
  const int* Lpi = pi();
  const int* Lpx = px();
  const int* Ls = rows();
  float* E = e_.data();
  for (int s = 0; s < nsuper(); ++s) {
    const int k1 = Super[s], nscol = Super[s + 1] - k1;
    const int psi = Lpi[s], nsrow = Lpi[s + 1] - psi, m = nsrow - nscol;
    const float* Lsx = Lx_.data + Lpx[s];
    if (nrhs == 1) {
      strsv_("L", "N", "N", &nscol, Lsx, &nsrow, Y + k1, &kInc);
      if (m == 0) continue;
      sgemv_("N", &m, &nscol, &kOne, Lsx + nscol, &nsrow, Y + k1, &kInc, &kZero, E, &kInc);
      for (int i = 0; i < m; ++i) Y[Ls[psi + nscol + i]] -= E[i];
    } else {
      strsm_("L", "L", "N", "N", &nscol, &nrhs, &kOne, Lsx, &nsrow, Y + k1, &n);
      if (m == 0) continue;
      sgemm_("N", "N", &m, &nrhs, &nscol, &kOne, Lsx + nscol, &nsrow, Y + k1, &n, &kZero, E, &m);
      for (int c = 0; c < nrhs; ++c)
        for (int i = 0; i < m; ++i)
          Y[Ls[psi + nscol + i] + static_cast<size_t>(c) * n] -= E[i + static_cast<size_t>(c) * m];
    }
  }
  for (int s = nsuper() - 1; s >= 0; --s) {
    const int k1 = Super[s], nscol = Super[s + 1] - k1;
    const int psi = Lpi[s], nsrow = Lpi[s + 1] - psi, m = nsrow - nscol;
    const float* Lsx = Lx_.data + Lpx[s];
    if (nrhs == 1) {
      if (m > 0) {
        for (int i = 0; i < m; ++i) E[i] = Y[Ls[psi + nscol + i]];
        sgemv_("T", &m, &nscol, &kMinusOne, Lsx + nscol, &nsrow, E, &kInc, &kOne, Y + k1, &kInc);
      }
      strsv_("L", "T", "N", &nscol, Lsx, &nsrow, Y + k1, &kInc);
    } else {
      if (m > 0) {
        for (int c = 0; c < nrhs; ++c)
          for (int i = 0; i < m; ++i)
            E[i + static_cast<size_t>(c) * m] = Y[Ls[psi + nscol + i] + static_cast<size_t>(c) * n];
        sgemm_("T", "N", &nscol, &nrhs, &m, &kMinusOne, Lsx + nscol, &nsrow, E, &m, &kOne, Y + k1, &n);
      }
      strsm_("L", "L", "T", "N", &nscol, &nrhs, &kOne, Lsx, &nsrow, Y + k1, &n);
    }
  }
}

// The same from the binary16 values, one right-hand side at a time: each solve streams
// the factor's 2 bytes per entry twice (forward, backward), widening them in registers.
// k right-hand sides stream it k times; a unit's nine-column χ solves run before
// compact(), on the float factor, so only single GMRES solves come here.
void FloatCholeskyFactor::substitute_half(float* Y, int nrhs) {
  for (int c = 0; c < nrhs; ++c) {
    float* y = Y + static_cast<size_t>(c) * n_;
    for (int s = 0; s < nsuper(); ++s) forward_half(s, y, e_.data());
    for (int s = nsuper() - 1; s >= 0; --s) backward_half(s, y, e_.data());
  }
}

// x = S P (L Lᵀ)⁻¹ Pᵀ S b: scaled and permuted into float, substituted, and back.
void FloatCholeskyFactor::solve(const double* B, double* X, int nrhs) {
  FE2_CHECK(ready_, "solve before factorize");
  const int n = n_;
  const int* P = perm();
  y_.resize(static_cast<size_t>(n) * nrhs);
  e_.resize(static_cast<size_t>(max_rows_) * nrhs);
  // Each column is divided by its largest |S b| before it is rounded (and multiplied back
  // after), so right-hand sides of any magnitude stay inside float's range.
  column_scale_.assign(nrhs, 1.0);
  for (int c = 0; c < nrhs; ++c) {
    const double* b = B + static_cast<size_t>(c) * n;
    double biggest = 0.0;
    for (int k = 0; k < n; ++k) biggest = std::max(biggest, std::abs(b[k] * scale_[k]));
    if (biggest > 0.0 && std::isfinite(biggest)) column_scale_[c] = biggest;
    const double inv = 1.0 / column_scale_[c];
    float* y = y_.data() + static_cast<size_t>(c) * n;
    for (int k = 0; k < n; ++k) y[k] = static_cast<float>(b[P[k]] * scale_[P[k]] * inv);
  }
  if (Lh_.data)  // after compact()
    substitute_half(y_.data(), nrhs);
  else
    substitute_float(y_.data(), nrhs);
  for (int c = 0; c < nrhs; ++c) {
    const float* y = y_.data() + static_cast<size_t>(c) * n;
    double* x = X + static_cast<size_t>(c) * n;
    for (int k = 0; k < n; ++k) x[P[k]] = static_cast<double>(y[k]) * scale_[P[k]] * column_scale_[c];
  }
}

}  // namespace

std::unique_ptr<SparseFactor> make_float_cholesky_factor(bool half_storage) {
  use_large_pages_in_suitesparse();
  return std::make_unique<FloatCholeskyFactor>(half_storage);
}

}  // namespace fe2
