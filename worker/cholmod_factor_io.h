#pragma once
// A CHOLMOD supernodal LLᵀ factor as bytes and back (checkpoints with
// output.checkpoint_factors), so that a restart solves with the very factor the run had
// instead of refactoring. Record layout (little-endian, inside a unit's state):
//
//   u64 n | u8 is_ll, is_super, is_monotonic | i32 ordering |
//   u64 nsuper, ssize, xsize, maxcsize, maxesize | f64 fl, lnz (the analysis' counts) |
//   Perm[n] | ColCount[n] | super[nsuper+1] | pi[nsuper+1] | px[nsuper+1] | s[ssize] |
//   x[xsize]                                  (each array: u64 length, then i32 or f64)
//
// The reader rebuilds the factor through CHOLMOD's own allocation path (as
// cholmod_super_symbolic and cholmod_super_numeric do) after checking every field: sizes
// against n, Perm a permutation, super/pi/px consistent, s sorted rows < n, maxcsize and
// maxesize recomputed, the pattern closed under elimination and holding K's (so that a
// later refactorization in place stays inside its arrays). A damaged record is an
// fe2::Error naming the field, never a crash.
#include "common/bytes.h"

#include <Eigen/Sparse>

struct cholmod_factor_struct;
struct cholmod_common_struct;
struct cholmod_sparse_struct;

namespace fe2 {

/// The counts cholmod_analyze leaves in cholmod_common (flops of one factorization,
/// nonzeros of L): part of the record, since the refresh policy's cost model reads them.
struct CholmodCounts {
  double fl = 0.0, lnz = 0.0;
};

/// Writes supernodal numeric LLᵀ factor `L` (CHOLMOD_INT, real). @throws Error otherwise.
void write_cholmod_factor(ByteWriter& w, const cholmod_factor_struct& L, const CholmodCounts& counts);

/// CHOLMOD's view of compressed K, no copy: its upper triangle (stype 1), int indices,
/// real double. Valid while K is alive and unchanged in size.
void cholmod_upper_view(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& K, cholmod_sparse_struct& A);

/// Reads a factor of a matrix with the pattern of `K` (full storage; CHOLMOD reads its
/// upper triangle). Returns a factor owned by the caller (cholmod_free_factor with `c`).
cholmod_factor_struct* read_cholmod_factor(ByteReader& r, const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& K,
                                           cholmod_common_struct& c, CholmodCounts& counts);

}  // namespace fe2
