#include "worker/abs_products.h"

#include <cmath>

namespace fe2 {

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
  const int* outer = K.outerIndexPtr();
  const double* value = K.valuePtr();
  Vec y(K.cols());
  // Eigen's reduction keeps several partial sums in vector registers; a plain loop would
  // wait on one add per entry.
  for (Eigen::Index c = 0; c < K.outerSize(); ++c)
    y[c] = Eigen::Map<const Eigen::ArrayXd>(value + outer[c], outer[c + 1] - outer[c]).abs().sum();
  return y;
}

}  // namespace fe2
