#pragma once
// A fill-reducing pivot order by nested dissection (METIS_NodeND) for a sparse matrix
// given by its pattern, to hand to a direct solver as its ordering.
//
// Why not ask the solver: Debian's MUMPS 5.5 is built with PORD and the AMD family only,
// and a request for METIS (ICNTL(7) = 5) falls back to PORD without an error (INFOG(7)
// = 4). On the paper-size macro PORD's order costs 1.83× the flops of METIS's, on a
// 2,997-DOF unit 1.6× (BENCHMARKS.md; docs/solvers.md, "Orderings").
#include <vector>

namespace fe2 {

/// The position of each of the n variables in the pivot order (a permutation of base..n−1+base),
/// from METIS_NodeND on the graph of A + Aᵀ without its diagonal, where A has an entry at
/// every (rows[k] − base, cols[k] − base): base 0 or 1, as the caller's solver counts
/// (MUMPS's PERM_IN is 1-based); duplicates and either triangle allowed.
/// Deterministic: the same pattern gives the same order (a fixed seed). Throws fe2::Error
/// naming METIS's status if it fails.
std::vector<int> nested_dissection_positions(int n, const std::vector<int>& rows,
                                             const std::vector<int>& cols, int base = 0);

}  // namespace fe2
