#pragma once
// What a micro unit model and each of its units will hold in memory, estimated from
// counts alone, before anything is allocated: a unit resolution inside the accepted
// range (e.g. 100³ hexahedra) would otherwise allocate until bad_alloc.
//
// Per model (shared by its units on a rank, peak while building): the hex mesh, the
// element geometry (8 Gauss points × ∇N), equations and scatter positions per element,
// the pattern of K and, transiently, its construction lists.
// Per unit: the state vectors (w, δw₁, w_committed, r), χ, G, H and the rollback
// copies (≈ 48 n doubles), three value arrays of K (K, K at the last refresh, K
// committed) plus K's own indices, and the sparse factor.
// K has ≈ 81 nonzeros per row (a hex-grid node couples with its 27 neighbours × 3).
// The factor's fill comes from a nested-dissection model of the periodic hex grid
// (fill_entries), calibrated against CHOLMOD with METIS ordering (a 27,780-DOF unit,
// 21³ hexahedra: ≈ 31 M entries ≈ 310 MB) to bound it from above (by up to ≈ 2.5×: a
// refused unit is refused early and clearly, a too-low estimate would end in bad_alloc),
// checked against CHOLMOD's own count in tests/worker/test_micro_model_plan.cpp; LU
// (UMFPACK) is counted twice that.
#include <array>
#include <string>

namespace fe2 {

struct MicroMemoryEstimate {
  long long nodes = 0;         ///< mesh nodes
  long long elements = 0;      ///< hexahedra
  long long dofs = 0;          ///< unknowns of a unit (3 per periodic node, minus the pinned one)
  double pattern_nnz = 0;      ///< nonzeros of K
  double factor_entries = 0;   ///< nonzeros of the factor (L, or L and U)
  double model_bytes = 0;      ///< shared by all units of the model on a rank
  double unit_bytes = 0;       ///< each unit
  double factor_bytes = 0;     ///< the sparse factor alone (part of unit_bytes): what a
                               ///< farm.factor_memory_budget must hold at least once

  /// Bytes of `units` units of this model on one rank (0 units: nothing).
  double bytes_for(long long units) const {
    return units > 0 ? model_bytes + static_cast<double>(units) * unit_bytes : 0.0;
  }
  /// "27780 DOF, K 2.2 M nonzeros, factor ≈ 31 M entries: model 40 MB + 330 MB per unit"
  std::string describe() const;
};

/// Entries of the Cholesky factor of a periodic hex grid with `cells` hexahedra per
/// axis (3 DOF per node), under nested dissection.
double fill_entries(std::array<long long, 3> cells);

/// The estimate for a unit of `cells` hexahedra per axis: a structured grid (built-in
/// cells), or the equivalent grid of a mesh file (same element count and aspect ratio).
/// `lu`: the factor is UMFPACK LU rather than CHOLMOD LLᵀ. `single`: it is a
/// single-precision factor (4-byte values: counted as half the double factor's bytes);
/// `half` with it: an LLᵀ factor kept in binary16 (a quarter; LU stays single).
MicroMemoryEstimate estimate_micro_memory(std::array<long long, 3> cells, long long nodes,
                                          long long elements, bool lu, bool single = false,
                                          bool half = false);

/// "310 MB", "5.4 GB".
std::string format_bytes(double bytes);

}  // namespace fe2
