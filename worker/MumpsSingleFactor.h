#pragma once
// A single-precision factor of the unit matrix K, to cut the cost of a factor: MUMPS
// smumps on one process (MPI_COMM_SELF), LDLᵀ without pivoting for the LLᵀ kind (K SPD) and LU
// otherwise, optionally with block low-rank compression. It is only ever used as the
// GMRES preconditioner (and first guess of χ): residuals, Krylov vectors and the
// answer stay double, so the converged unit answer is the double-factor one to the
// GMRES tolerance; the float factor costs extra iterations, not accuracy.
#include "worker/SparseFactor.h"

#include <memory>

namespace fe2 {

/// `symmetric`: K is symmetric positive definite (its upper triangle is passed, SYM = 1); otherwise LU
/// (SYM = 0). `blr_tolerance` > 0 turns on block low-rank factor and solve (ICNTL(35) =
/// 2) with that dropping threshold (CNTL(7)); 0 is the plain full-rank factor.
std::unique_ptr<SparseFactor> make_mumps_single_factor(bool symmetric, double blr_tolerance);

}  // namespace fe2
