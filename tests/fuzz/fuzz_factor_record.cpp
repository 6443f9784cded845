// The CHOLMOD factor record of checkpoints with output.checkpoint_factors
// (worker/cholmod_factor_io.h) on arbitrary bytes, against one fixed SPD matrix (a 3D
// 7-point Laplacian, 5×5×5): a factor whose every field is consistent, or an fe2::Error.
// An accepted record must then survive what a restarted unit does with it: a solve, and
// a refactorization in place (the update workspace sized by the record's maxcsize), and
// CHOLMOD's own cholmod_check_factor (CHOLMOD itself is not instrumented). The seed (corpus/factor_record/laplacian_5.bin) is that matrix's
// factor; `fuzz_factor_record --write-seed FILE` writes it again.
#include "tests/fuzz/fuzz_support.h"
#include "worker/cholmod_factor_io.h"

#include <suitesparse/cholmod.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <vector>

using namespace fe2;

namespace {

using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

const Sparse& laplacian() {
  static const Sparse K = [] {
    const int m = 5, n = m * m * m;
    std::vector<Eigen::Triplet<double>> t;
    auto id = [&](int i, int j, int k) { return i + m * (j + m * k); };
    for (int k = 0; k < m; ++k)
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
          const int a = id(i, j, k);
          t.emplace_back(a, a, 6.5);
          if (i + 1 < m) t.emplace_back(a, id(i + 1, j, k), -1), t.emplace_back(id(i + 1, j, k), a, -1);
          if (j + 1 < m) t.emplace_back(a, id(i, j + 1, k), -1), t.emplace_back(id(i, j + 1, k), a, -1);
          if (k + 1 < m) t.emplace_back(a, id(i, j, k + 1), -1), t.emplace_back(id(i, j, k + 1), a, -1);
        }
    Sparse K(n, n);
    K.setFromTriplets(t.begin(), t.end());
    K.makeCompressed();
    return K;
  }();
  return K;
}

cholmod_sparse view(const Sparse& K) {
  cholmod_sparse A;
  cholmod_upper_view(K, A);
  return A;
}

struct Common {
  cholmod_common c;
  Common() {
    cholmod_start(&c);
    c.supernodal = CHOLMOD_SUPERNODAL;
    c.print = 0;
    c.error_handler = nullptr;
  }
  ~Common() { cholmod_finish(&c); }
};

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  // --write-seed FILE: the factor of the fixed matrix, as a checkpoint stores it.
  for (int k = 1; k + 1 < *argc; ++k)
    if (std::strcmp((*argv)[k], "--write-seed") == 0) {
      Common c;
      cholmod_sparse A = view(laplacian());
      cholmod_factor* L = cholmod_analyze(&A, &c.c);
      cholmod_factorize(&A, L, &c.c);
      Bytes b;
      ByteWriter w(b);
      write_cholmod_factor(w, *L, {c.c.fl, c.c.lnz});
      std::ofstream((*argv)[k + 1], std::ios::binary).write(reinterpret_cast<const char*>(b.data()), b.size());
      cholmod_free_factor(&L, &c.c);
      std::exit(0);
    }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static Common c;
  const Sparse& K = laplacian();
  ByteReader r(reinterpret_cast<const std::byte*>(data), size, "factor record");
  cholmod_factor* L = nullptr;
  CholmodCounts counts;
  fuzz::expect_only<Error>([&] { L = read_cholmod_factor(r, K, c.c, counts); });
  if (!L) return 0;
  fuzz::require(L->n == static_cast<size_t>(K.rows()) && L->is_super && L->xtype == CHOLMOD_REAL,
                "an accepted record is a supernodal numeric factor of K's size");
  // CHOLMOD is not instrumented: its own consistency check stands in for ASan inside it.
  fuzz::require(cholmod_check_factor(L, &c.c), "CHOLMOD's cholmod_check_factor accepts an accepted record");
  std::vector<double> b(L->n, 1.0);
  cholmod_dense B{};
  B.nrow = B.d = B.nzmax = L->n;
  B.ncol = 1;
  B.x = b.data();
  B.xtype = CHOLMOD_REAL;
  B.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* X = cholmod_solve(CHOLMOD_A, L, &B, &c.c);
  if (X) cholmod_free_dense(&X, &c.c);
  cholmod_sparse A = view(K);
  cholmod_factorize(&A, L, &c.c);  // in place, on the record's analysis: K is SPD
  fuzz::require(c.c.status == CHOLMOD_OK, "K refactors on an accepted record's analysis");
  cholmod_free_factor(&L, &c.c);
  return 0;
}
