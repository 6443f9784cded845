#pragma once
// |K| products: the scale of round-off in K x (eps·|K||x| bounds the error of each
// entry of a computed K x), from which a unit's residual and solve floors are made.
#include "common/linalg/gmres.h"  // Vec
#include "worker/SparseFactor.h"

namespace fe2 {

/// |K| |v| (entry-wise absolute values).
Vec abs_times(const SparseMatrix& K, const Vec& v);

/// |K| 𝟙, the row sums of |K|. When K is symmetric (`symmetric`; a unit's K is, to
/// round-off, when every law has major symmetry) these are its column sums: one
/// sequential pass over the values, without reading an index or scattering into the
/// result.
Vec abs_row_sums(const SparseMatrix& K, bool symmetric);

/// y = K x, and in the same pass over K's values `abs_sums` = abs_row_sums(K, symmetric)
/// (bit for bit both): a unit's first Step 1 product gives its residual floor for
/// the price of one more add per entry instead of a second 18 MB read (at ≈ 26k DOF).
void times_and_abs_row_sums(const SparseMatrix& K, const Vec& x, Vec& y, Vec& abs_sums,
                            bool symmetric);

}  // namespace fe2
