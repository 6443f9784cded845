#include "worker/abs_products.h"

#include <cmath>

namespace fe2 {

namespace {
/// Σ_i |K_ic|: Eigen's reduction keeps several partial sums in vector registers, where
/// a plain loop would wait on one add per entry.
double column_abs_sum(const SparseMatrix& K, Eigen::Index c) {
  const int* outer = K.outerIndexPtr();
  return Eigen::Map<const Eigen::ArrayXd>(K.valuePtr() + outer[c], outer[c + 1] - outer[c]).abs().sum();
}
}  // namespace

Vec abs_times(const SparseMatrix& K, const Vec& v) {
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  const double* value = K.valuePtr();
  Vec y = Vec::Zero(K.rows());
  for (Eigen::Index c = 0; c < K.outerSize(); ++c) {
    const double vc = std::abs(v[c]);
    if (vc == 0.0) continue;  // Step 1 starts from x = 0: its floor costs nothing
    for (int k = outer[c]; k < outer[c + 1]; ++k) y[inner[k]] += std::abs(value[k]) * vc;
  }
  return y;
}

Vec abs_row_sums(const SparseMatrix& K, bool symmetric) {
  if (!symmetric) return abs_times(K, Vec::Ones(K.cols()));
  Vec y(K.cols());
  for (Eigen::Index c = 0; c < K.outerSize(); ++c) y[c] = column_abs_sum(K, c);
  return y;
}

void times_and_abs_row_sums(const SparseMatrix& K, const Vec& x, Vec& y, Vec& abs_sums,
                            bool symmetric) {
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  const double* value = K.valuePtr();
  y.setZero(K.rows());
  abs_sums.setZero(K.rows());
  // Column by column, as Eigen's own product (the same sums in the same order).
  for (Eigen::Index c = 0; c < K.outerSize(); ++c) {
    const double xc = x[c];
    if (symmetric) {
      for (int k = outer[c]; k < outer[c + 1]; ++k) y[inner[k]] += value[k] * xc;
      abs_sums[c] = column_abs_sum(K, c);  // the column just read, from cache
    } else {
      for (int k = outer[c]; k < outer[c + 1]; ++k) {
        y[inner[k]] += value[k] * xc;
        abs_sums[inner[k]] += std::abs(value[k]);
      }
    }
  }
}

}  // namespace fe2
