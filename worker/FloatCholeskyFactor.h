#pragma once
// A single-precision supernodal LLᵀ of the unit matrix K, used only as the GMRES
// preconditioner (unit.solver.precision "single"; residuals and the answer stay double).
//
// Why not a library: Debian 12's CHOLMOD (3.0.14) factors in double only, and MUMPS's
// single-precision LDLᵀ measured 1.29× CHOLMOD's double refresh on the 27,780-DOF unit
// (docs/benchmarks/2026-11-micro-unit.md, "Single-precision factor"). This class keeps CHOLMOD's symbolic
// analysis (the fill-reducing ordering it picks, METIS on the units measured;
// supernodes; row patterns) and does the numeric work itself,
// supernode by supernode in the left-looking order CHOLMOD's own numeric factorization
// uses, with the single-precision BLAS/LAPACK kernels (ssyrk, sgemm, spotrf, strsm):
// twice the SIMD width and half the memory traffic of the double factor.
//
// K is scaled symmetrically to unit diagonal before it is rounded to float,
// K̃ = S K S with S = diag(K)^(-1/2), so that entries of any magnitude (units in Pa or
// MPa, contrasts of 10³ and more) stay inside float's range; a solve returns S K̃⁻¹ S b,
// each right-hand side normalised before it is rounded.
#include "worker/SparseFactor.h"

#include <memory>

namespace fe2 {

/// K symmetric positive definite (the LLᵀ kind's contract). factorize() throws
/// NumericalError naming the leading minor if float LLᵀ of S K S breaks down.
/// `half_storage` (unit.solver.precision "half"): factored in float, then kept in IEEE
/// binary16 (half the float factor's bytes; each solve converts 64 columns of a
/// supernode at a time into a float panel).
std::unique_ptr<SparseFactor> make_float_cholesky_factor(bool half_storage = false);

}  // namespace fe2
