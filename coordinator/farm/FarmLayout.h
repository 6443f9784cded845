#pragma once
// Who does what in a run of N ranks (DESIGN §3): the first n_c ranks coordinate
// (own macro elements exclusively, paper Eq. 12, and solve the Schur system together);
// the worker ranks hold the units — every rank, or only the non-coordinators. Computed
// identically on every rank from the spec and N, so no rank has to be told.
#include "coordinator/RunSpec.h"
#include "coordinator/macro/MacroPartition.h"

#include <vector>

namespace fe2 {

struct FarmLayout {
  int ranks = 1;
  int coordinators = 1;
  std::vector<int> worker_ranks;         ///< world ranks that hold units
  std::vector<int> coordinator_of_element;  ///< per macro element: owning coordinator's world rank
  std::vector<int> coordinator_of_unit;  ///< per unit (= integration point): its element's coordinator
  /// per unit: world rank holding it at the start (a local unit: its coordinator)
  std::vector<int> initial_worker_of_unit;
  /// per unit: 1 if its coordinator evaluates it in place (a macro-law point with
  /// farm.macro_law_points "local"; coordinator/LocalPoints.h): never a job, never moved
  std::vector<char> local_unit;

  bool is_coordinator(int rank) const { return rank < coordinators; }
  bool is_local(int unit) const { return local_unit[static_cast<size_t>(unit)] != 0; }
  /// Units that travel through the farm (placed on workers, rebalanced), ascending.
  std::vector<int> farm_units() const;
  bool is_worker(int rank) const;
  /// Units (points) owned by coordinator `c`, ascending.
  std::vector<int> owned_units(int c) const;
  /// Coordinator `c`'s share of the macro mesh (every term assembles over it).
  MacroPartition partition(int c) const { return MacroPartition(c, coordinators, coordinator_of_element); }

  /// Throws InputError (before any work) if the coordinator count cannot work.
  /// `coordinators_override` > 0 replaces the spec's farm.coordinators.
  static FarmLayout make(const RunSpec& spec, int ranks, int coordinators_override = 0);
};

/// Exclusive partition of the tets into `parts` compact parts of about equal total
/// `weight` (METIS on the dual graph; empty weights: every element alike; contiguous
/// blocks when METIS is not needed). Deterministic.
std::vector<int> partition_elements(const TetMesh& mesh, int parts, const std::vector<int>& weight = {});

}  // namespace fe2
