#include "worker/cholmod_factor_io.h"

#include "common/error.h"

#include <suitesparse/cholmod.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

namespace fe2 {

namespace {

constexpr const char* kWhat = "stored CHOLMOD factor";

[[noreturn]] void damaged(const std::string& why) {
  throw Error(fmt::format("{}: {} (a damaged checkpoint record)", kWhat, why));
}

template <class T>
void put_ints(ByteWriter& w, const void* p, size_t n) {
  w.put_array(static_cast<const T*>(p), n);
}

/// Whether `row` is among the sorted rows [first, last).
bool has_row(const int* first, const int* last, int row) {
  const int* at = std::lower_bound(first, last, row);
  return at != last && *at == row;
}

/// The supernodal structure read from a record, checked before CHOLMOD sees any of it.
struct Structure {
  size_t n = 0, nsuper = 0, ssize = 0, xsize = 0, maxcsize = 0, maxesize = 0;
  std::vector<int> perm, colcount, super, pi, px, s;
  std::vector<int> super_of;  ///< column -> its supernode

  const int* rows_begin(size_t k) const { return s.data() + pi[k]; }
  const int* rows_end(size_t k) const { return s.data() + pi[k + 1]; }

  void check_arrays() {
    std::vector<char> seen(n, 0);
    for (size_t k = 0; k < n; ++k) {
      const int p = perm[k];
      if (p < 0 || static_cast<size_t>(p) >= n || seen[p]) damaged(fmt::format("Perm[{}] = {} is not a permutation of 0..{}", k, p, n - 1));
      seen[p] = 1;
      if (colcount[k] < 1 || static_cast<size_t>(colcount[k]) > n - k)
        damaged(fmt::format("ColCount[{}] = {}, expected 1..{}", k, colcount[k], n - k));
    }
    if (super[0] != 0 || static_cast<size_t>(super[nsuper]) != n)
      damaged(fmt::format("supernodes span columns {}..{}, expected 0..{}", super[0], super[nsuper], n));
    if (pi[0] != 0 || px[0] != 0) damaged(fmt::format("pi[0] = {}, px[0] = {}, expected 0", pi[0], px[0]));
    super_of.assign(n, 0);
    for (size_t k = 0; k < nsuper; ++k) {
      const int64_t ncol = int64_t{super[k + 1]} - super[k];
      const int64_t nrow = int64_t{pi[k + 1]} - pi[k];
      if (ncol < 1) damaged(fmt::format("super is not increasing at supernode {} ({} then {})", k, super[k], super[k + 1]));
      if (nrow < ncol || int64_t{pi[k + 1]} > static_cast<int64_t>(ssize))
        damaged(fmt::format("supernode {} has {} rows for {} columns (pi {}..{}, ssize {})", k, nrow, ncol, pi[k],
                            pi[k + 1], ssize));
      if (int64_t{px[k + 1]} - px[k] != nrow * ncol)
        damaged(fmt::format("px[{}] - px[{}] = {}, expected {} rows × {} columns", k + 1, k,
                            int64_t{px[k + 1]} - px[k], nrow, ncol));
      for (int j = super[k]; j < super[k + 1]; ++j) super_of[j] = static_cast<int>(k);
    }
    if (ssize != std::max<size_t>(1, pi[nsuper]) || xsize != std::max<size_t>(1, px[nsuper]))
      damaged(fmt::format("ssize {} and xsize {}, expected {} and {}", ssize, xsize, std::max<size_t>(1, pi[nsuper]),
                          std::max<size_t>(1, px[nsuper])));
    for (size_t k = 0; k < nsuper; ++k) {  // the diagonal block, then rows below it, sorted
      const int* r = rows_begin(k);
      const int ncol = super[k + 1] - super[k], nrow = pi[k + 1] - pi[k];
      for (int i = 0; i < nrow; ++i) {
        const int expect_min = i < ncol ? super[k] + i : r[i - 1] + 1;
        if ((i < ncol && r[i] != expect_min) || r[i] < expect_min || static_cast<size_t>(r[i]) >= n)
          damaged(fmt::format("row {} of supernode {} is {} (columns {}..{}, n = {})", i, k, r[i], super[k],
                              super[k + 1] - 1, n));
      }
    }
  }

  /// maxcsize and maxesize as cholmod_super_symbolic computes them (the workspace sizes of
  /// a refactorization and a solve), and the closure every update from a supernode to an
  /// ancestor relies on: its rows from that ancestor down are all rows of the ancestor.
  void check_updates() const {
    size_t csize_max = 1, esize_max = 1;
    for (size_t d = 0; d < nsuper; ++d) {
      const int ncol = super[d + 1] - super[d];
      const int* r = rows_begin(d);
      const int pend = pi[d + 1] - pi[d];
      int p = ncol;
      esize_max = std::max<size_t>(esize_max, static_cast<size_t>(pend - p));
      while (p < pend) {
        const int a = super_of[r[p]];
        int q = p;
        while (q < pend && super_of[r[q]] == a) ++q;
        csize_max = std::max(csize_max, static_cast<size_t>(q - p) * static_cast<size_t>(pend - p));
        for (int i = p; i < pend; ++i)
          if (!has_row(rows_begin(a), rows_end(a), r[i]))
            damaged(fmt::format("supernode {} updates supernode {} in row {}, which that supernode lacks", d, a, r[i]));
        p = q;
      }
    }
    if (csize_max != maxcsize || esize_max != maxesize)
      damaged(fmt::format("maxcsize {} and maxesize {}, the pattern gives {} and {}", maxcsize, maxesize, csize_max,
                          esize_max));
  }

  /// Every entry of K's upper triangle, permuted, lies in the pattern (CHOLMOD
  /// assembles K into it on a refactorization).
  void check_holds(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& K) const {
    std::vector<int> inverse(n);
    for (size_t k = 0; k < n; ++k) inverse[perm[k]] = static_cast<int>(k);
    const int* outer = K.outerIndexPtr();
    const int* inner = K.innerIndexPtr();
    for (Eigen::Index j = 0; j < K.outerSize(); ++j)
      for (int p = outer[j]; p < outer[j + 1]; ++p) {
        const int i = inner[p];
        if (i > j) continue;  // CHOLMOD reads the upper triangle (stype 1)
        const int a = inverse[i], b = inverse[j];
        const int col = std::min(a, b), row = std::max(a, b);
        const size_t k = super_of[col];
        if (!has_row(rows_begin(k), rows_end(k), row))
          damaged(fmt::format("K({}, {}) falls outside the factor's pattern", i, j));
      }
  }
};

struct FactorDeleter {
  cholmod_common* c;
  void operator()(cholmod_factor* L) const { cholmod_free_factor(&L, c); }
};

}  // namespace

void write_cholmod_factor(ByteWriter& w, const cholmod_factor& L, const CholmodCounts& counts) {
  FE2_CHECK(L.is_super && L.is_ll && L.xtype == CHOLMOD_REAL && L.itype == CHOLMOD_INT && L.dtype == CHOLMOD_DOUBLE,
            "write_cholmod_factor: a supernodal numeric LLᵀ int/double factor is expected");
  w.put<uint64_t>(L.n);
  w.put<uint8_t>(L.is_ll ? 1 : 0);
  w.put<uint8_t>(L.is_super ? 1 : 0);
  w.put<uint8_t>(L.is_monotonic ? 1 : 0);
  w.put<int32_t>(L.ordering);
  for (size_t v : {L.nsuper, L.ssize, L.xsize, L.maxcsize, L.maxesize}) w.put<uint64_t>(v);
  w.put(counts.fl);
  w.put(counts.lnz);
  put_ints<int>(w, L.Perm, L.n);
  put_ints<int>(w, L.ColCount, L.n);
  put_ints<int>(w, L.super, L.nsuper + 1);
  put_ints<int>(w, L.pi, L.nsuper + 1);
  put_ints<int>(w, L.px, L.nsuper + 1);
  put_ints<int>(w, L.s, L.ssize);
  w.put_array(static_cast<const double*>(L.x), L.xsize);
}

cholmod_factor* read_cholmod_factor(ByteReader& r, const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& K,
                                    cholmod_common& c, CholmodCounts& counts) {
  Structure st;
  st.n = r.get<uint64_t>();
  if (st.n != static_cast<uint64_t>(K.rows()) || K.rows() != K.cols() || st.n == 0)
    damaged(fmt::format("n = {}, the unit matrix has {} rows", st.n, K.rows()));
  const auto is_ll = r.get<uint8_t>(), is_super = r.get<uint8_t>(), is_monotonic = r.get<uint8_t>();
  if (is_ll != 1 || is_super != 1 || is_monotonic > 1)
    damaged(fmt::format("is_ll {}, is_super {}, is_monotonic {}: a supernodal LLᵀ factor is expected", is_ll, is_super,
                        is_monotonic));
  const auto ordering = r.get<int32_t>();
  if (ordering < CHOLMOD_NATURAL || ordering > CHOLMOD_POSTORDERED)
    damaged(fmt::format("ordering {}, expected {}..{}", ordering, CHOLMOD_NATURAL, CHOLMOD_POSTORDERED));
  st.nsuper = r.get<uint64_t>();
  st.ssize = r.get<uint64_t>();
  st.xsize = r.get<uint64_t>();
  st.maxcsize = r.get<uint64_t>();
  st.maxesize = r.get<uint64_t>();
  if (st.nsuper < 1 || st.nsuper > st.n) damaged(fmt::format("nsuper = {} for n = {}", st.nsuper, st.n));
  if (st.ssize > static_cast<uint64_t>(INT_MAX) || st.xsize > static_cast<uint64_t>(INT_MAX))
    damaged(fmt::format("ssize {} or xsize {} beyond CHOLMOD's int range", st.ssize, st.xsize));
  counts.fl = r.get<double>();
  counts.lnz = r.get<double>();
  if (!(std::isfinite(counts.fl) && counts.fl >= 0 && std::isfinite(counts.lnz) && counts.lnz >= 0))
    damaged(fmt::format("flop count {} and lnz {}, expected finite and >= 0", counts.fl, counts.lnz));
  const auto n = static_cast<int64_t>(st.n), ns = static_cast<int64_t>(st.nsuper);
  st.perm = r.get_array<int>(n);
  st.colcount = r.get_array<int>(n);
  st.super = r.get_array<int>(ns + 1);
  st.pi = r.get_array<int>(ns + 1);
  st.px = r.get_array<int>(ns + 1);
  st.s = r.get_array<int>(static_cast<int64_t>(st.ssize));
  st.check_arrays();
  if (ordering == CHOLMOD_NATURAL)  // CHOLMOD then factors K unpermuted, whatever Perm says
    for (size_t k = 0; k < st.n; ++k)
      if (st.perm[k] != static_cast<int>(k))
        damaged(fmt::format("ordering natural, but Perm[{}] = {}", k, st.perm[k]));
  st.check_updates();
  st.check_holds(K);

  // Through CHOLMOD's allocation path: simplicial symbolic (Perm, ColCount), then
  // supernodal symbolic (super, pi, px, s), then numeric (x).
  std::unique_ptr<cholmod_factor, FactorDeleter> L(cholmod_allocate_factor(st.n, &c), FactorDeleter{&c});
  if (!L || c.status < CHOLMOD_OK) throw Error(fmt::format("{}: cholmod_allocate_factor failed with status {}", kWhat, c.status));
  FE2_CHECK(L->itype == CHOLMOD_INT, "CHOLMOD int factor expected");
  std::memcpy(L->Perm, st.perm.data(), st.n * sizeof(int));
  std::memcpy(L->ColCount, st.colcount.data(), st.n * sizeof(int));
  L->ordering = ordering;
  L->nsuper = st.nsuper;
  L->ssize = st.ssize;
  L->xsize = st.xsize;
  if (!cholmod_change_factor(CHOLMOD_PATTERN, 1, 1, 1, 1, L.get(), &c))
    throw Error(fmt::format("{}: cholmod_change_factor (supernodal pattern) failed with status {}", kWhat, c.status));
  L->maxcsize = st.maxcsize;  // after the change, which zeroes them
  L->maxesize = st.maxesize;
  std::memcpy(L->super, st.super.data(), (st.nsuper + 1) * sizeof(int));
  std::memcpy(L->pi, st.pi.data(), (st.nsuper + 1) * sizeof(int));
  std::memcpy(L->px, st.px.data(), (st.nsuper + 1) * sizeof(int));
  std::memcpy(L->s, st.s.data(), st.ssize * sizeof(int));
  if (!cholmod_change_factor(CHOLMOD_REAL, 1, 1, 1, 1, L.get(), &c))
    throw Error(fmt::format("{}: cholmod_change_factor (numeric) failed with status {}", kWhat, c.status));
  auto* x = static_cast<double*>(L->x);
  r.get_array_into(x, st.xsize);
  for (size_t k = 0; k < st.xsize; ++k)
    if (!std::isfinite(x[k])) damaged(fmt::format("x[{}] = {}", k, x[k]));
  L->is_monotonic = is_monotonic;
  return L.release();
}

void cholmod_upper_view(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& K, cholmod_sparse& A) {
  A = cholmod_sparse{};
  A.nrow = static_cast<size_t>(K.rows());
  A.ncol = static_cast<size_t>(K.cols());
  A.nzmax = static_cast<size_t>(K.nonZeros());
  A.p = const_cast<int*>(K.outerIndexPtr());
  A.i = const_cast<int*>(K.innerIndexPtr());
  A.x = const_cast<double*>(K.valuePtr());
  A.stype = 1;
  A.itype = CHOLMOD_INT;
  A.xtype = CHOLMOD_REAL;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
}

}  // namespace fe2
