// Large arrays on 2 MiB pages (worker/large_pages.h) and what units assemble into
// (MicroModel::zero_matrix). Whether the kernel grants huge pages is its choice, so the
// tests hold what the code promises whatever it grants: alignment, contents kept across
// SuiteSparse's realloc, zeros from its calloc, and a zero matrix with the pattern.
#include "tests/worker/unit_fixtures.h"
#include "worker/SparseFactor.h"
#include "worker/large_pages.h"

#include <suitesparse/SuiteSparse_config.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace fe2 {
namespace {

TEST(LargePages, LargeAllocationsStartOnA2MiBBoundary) {
  ASSERT_TRUE(large_pages_enabled());  // the tests run without FE2_LARGE_PAGES=0
  for (size_t bytes : {kLargePageBytes, 3 * kLargePageBytes + 17, size_t{50} << 20}) {
    auto* p = static_cast<unsigned char*>(large_page_alloc(bytes));
    ASSERT_NE(p, nullptr);
    EXPECT_EQ(reinterpret_cast<uintptr_t>(p) % kLargePageBytes, 0u) << bytes;
    std::memset(p, 0xab, bytes);  // the whole of it is ours to write
    EXPECT_EQ(p[bytes - 1], 0xab);
    std::free(p);
  }
  void* small = large_page_alloc(100);  // below the threshold: plain malloc
  ASSERT_NE(small, nullptr);
  std::free(small);
}

TEST(LargePages, SuiteSparseKeepsContentsAndZeros) {
  use_large_pages_in_suitesparse();
  EXPECT_EQ(SuiteSparse_config.free_func, &std::free);
  // realloc across the threshold and within it, up and down: the contents stay.
  const size_t n0 = 300000, n1 = 900000, n2 = 700000;  // doubles: 2.4 MB, 7.2 MB, 5.6 MB
  auto* a = static_cast<double*>(SuiteSparse_config.malloc_func(n0 * sizeof(double)));
  ASSERT_NE(a, nullptr);
  for (size_t k = 0; k < n0; ++k) a[k] = static_cast<double>(k) + 0.5;
  a = static_cast<double*>(SuiteSparse_config.realloc_func(a, n1 * sizeof(double)));
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(a) % kLargePageBytes, 0u);
  for (size_t k = 0; k < n0; ++k) ASSERT_EQ(a[k], static_cast<double>(k) + 0.5) << k;
  a = static_cast<double*>(SuiteSparse_config.realloc_func(a, n2 * sizeof(double)));
  ASSERT_NE(a, nullptr);
  for (size_t k = 0; k < n0; ++k) ASSERT_EQ(a[k], static_cast<double>(k) + 0.5) << k;
  a = static_cast<double*>(SuiteSparse_config.realloc_func(a, 1000 * sizeof(double)));
  ASSERT_NE(a, nullptr);
  for (size_t k = 0; k < 1000; ++k) ASSERT_EQ(a[k], static_cast<double>(k) + 0.5) << k;
  SuiteSparse_config.free_func(a);

  // calloc: zeros, also where malloc may hand back memory a freed block dirtied.
  auto* dirty = static_cast<double*>(SuiteSparse_config.malloc_func(n1 * sizeof(double)));
  ASSERT_NE(dirty, nullptr);
  std::fill_n(dirty, n1, 1.0);
  SuiteSparse_config.free_func(dirty);
  auto* z = static_cast<double*>(SuiteSparse_config.calloc_func(n1, sizeof(double)));
  ASSERT_NE(z, nullptr);
  for (size_t k = 0; k < n1; ++k) ASSERT_EQ(z[k], 0.0) << k;
  SuiteSparse_config.free_func(z);
  EXPECT_EQ(SuiteSparse_config.calloc_func(SIZE_MAX / 2, 4), nullptr);  // count × size overflows
}

TEST(LargePages, ZeroMatrixIsThePatternWithZeros) {
  // Large enough for whole 2 MiB pages inside K's values (they are advised and discarded).
  const MicroModelPtr model = test::two_cell_model({}, {16, 12, 12});
  const SparseMatrix& P = model->pattern();
  ASSERT_GT(P.nonZeros() * sizeof(double), 2 * kLargePageBytes);
  for (int round = 0; round < 2; ++round) {  // the second may reuse the first's memory
    const SparseMatrix K = model->zero_matrix();
    ASSERT_EQ(K.rows(), P.rows());
    ASSERT_EQ(K.nonZeros(), P.nonZeros());
    EXPECT_TRUE(K.isCompressed());
    EXPECT_EQ(0, std::memcmp(K.outerIndexPtr(), P.outerIndexPtr(), sizeof(int) * (P.cols() + 1)));
    EXPECT_EQ(0, std::memcmp(K.innerIndexPtr(), P.innerIndexPtr(), sizeof(int) * P.nonZeros()));
    for (Eigen::Index k = 0; k < K.nonZeros(); ++k) ASSERT_EQ(K.valuePtr()[k], 0.0) << k;
    SparseMatrix dirty = K;
    std::fill_n(dirty.valuePtr(), dirty.nonZeros(), 3.0);
  }
}

}  // namespace
}  // namespace fe2
