// The binary16 column kernels of a factor kept in half precision (worker/binary16_columns.h)
// against plain double loops over the same rounded values: every column count the solves
// use, and lengths that leave every kind of tail after the 8- and 16-row vector loops.
#include "worker/binary16_columns.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace fe2 {
namespace {

struct Columns {
  int n = 0;
  std::ptrdiff_t ld = 0;
  std::vector<uint16_t> L;  ///< ncols columns of ld entries, binary16
  std::vector<const uint16_t*> columns;
  std::vector<float> x, w;
};

Columns random_columns(int ncols, int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Columns c;
  c.n = n;
  c.ld = n + 3;  // columns apart, as in a supernode
  std::vector<float> values(static_cast<size_t>(c.ld) * ncols);
  for (float& v : values) v = u(gen);
  c.L.resize(values.size());
  floats_to_half(values.data(), c.L.data(), values.size());
  for (int k = 0; k < ncols; ++k) {
    c.columns.push_back(c.L.data() + k * c.ld);
    c.x.push_back(u(gen));
  }
  for (int i = 0; i < n; ++i) c.w.push_back(u(gen));
  return c;
}

TEST(Binary16Columns, RoundingIsToNearestAndExactOnRepresentableValues) {
  const std::vector<float> from = {1.0f, -0.5f, 2049.0f, 1.0f + 1.0f / 4096, 65504.0f, 1e-8f,
                                   3.0f, 0.1f, 1.0f / 3};
  std::vector<uint16_t> h(from.size());
  floats_to_half(from.data(), h.data(), from.size());  // 8 vectorized, 1 scalar
  EXPECT_EQ(half_to_float(h[0]), 1.0f);
  EXPECT_EQ(half_to_float(h[1]), -0.5f);
  EXPECT_EQ(half_to_float(h[2]), 2048.0f);  // 11 significant bits: a tie, to even
  EXPECT_EQ(half_to_float(h[3]), 1.0f);     // below half an ulp (2⁻¹¹)
  EXPECT_EQ(half_to_float(h[4]), 65504.0f);
  EXPECT_EQ(half_to_float(h[5]), 0.0f);     // under the smallest subnormal (6e-8)
  EXPECT_EQ(half_to_float(h[6]), 3.0f);
  EXPECT_NEAR(half_to_float(h[7]), 0.1f, 0.1f * 0x1p-11f);
  EXPECT_NEAR(half_to_float(h[8]), 1.0f / 3, 0x1p-13f);
}

TEST(Binary16Columns, SubtractAndDotMatchDoubleLoopsOverTheRoundedValues) {
  for (int ncols = 1; ncols <= kMaxHalfColumns; ++ncols)
    for (const int n : {0, 1, 7, 8, 9, 15, 16, 17, 31, 100, 1001}) {
      Columns c = random_columns(ncols, n, 100 * ncols + n);
      std::vector<double> w_ref(c.w.begin(), c.w.end()), d_ref(ncols, 0.0);
      for (int k = 0; k < ncols; ++k)
        for (int i = 0; i < n; ++i) {
          const double Lik = half_to_float(c.L[k * c.ld + i]);
          w_ref[i] -= Lik * c.x[k];
          d_ref[k] += Lik * c.w[i];
        }
      std::vector<float> d(kMaxHalfColumns, -1.0f);
      dot_half_columns(ncols, n, c.columns.data(), c.w.data(), d.data());
      subtract_half_columns(ncols, n, c.columns.data(), c.x.data(), c.w.data());
      // float accumulation of n products of size ≤ 1: a few float ulps of n.
      const double tol = 4 * n * 0x1p-24 + 1e-7;
      for (int i = 0; i < n; ++i)
        EXPECT_NEAR(c.w[i], w_ref[i], tol) << ncols << " columns, n " << n << ", row " << i;
      for (int k = 0; k < ncols; ++k)
        EXPECT_NEAR(d[k], d_ref[k], tol) << ncols << " columns, n " << n << ", column " << k;
    }
}

TEST(Binary16Columns, MoreColumnsThanTheKernelsTakeAreRefused) {
  Columns c = random_columns(1, 8, 1);
  std::vector<const uint16_t*> columns(kMaxHalfColumns + 1, c.L.data());
  std::vector<float> x(kMaxHalfColumns + 1, 1.0f), d(kMaxHalfColumns + 1);
  EXPECT_ANY_THROW(subtract_half_columns(kMaxHalfColumns + 1, 8, columns.data(), x.data(),
                                         c.w.data()));
  EXPECT_ANY_THROW(dot_half_columns(0, 8, columns.data(), c.w.data(), d.data()));
}

}  // namespace
}  // namespace fe2
