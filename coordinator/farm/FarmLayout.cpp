#include "coordinator/farm/FarmLayout.h"

#include "coordinator/farm/Rebalancer.h"
#include "coordinator/macro/macro_scene.h"

#include <metis.h>

#include <algorithm>
#include <functional>

namespace fe2 {

bool FarmLayout::is_worker(int rank) const {
  return std::binary_search(worker_ranks.begin(), worker_ranks.end(), rank);
}

std::vector<int> FarmLayout::owned_units(int c) const {
  std::vector<int> out;
  for (size_t u = 0; u < coordinator_of_unit.size(); ++u)
    if (coordinator_of_unit[u] == c) out.push_back(static_cast<int>(u));
  return out;
}

std::vector<int> FarmLayout::farm_units() const {
  std::vector<int> out;
  for (size_t u = 0; u < local_unit.size(); ++u)
    if (!local_unit[u]) out.push_back(static_cast<int>(u));
  return out;
}

std::vector<int> partition_elements(const TetMesh& mesh, int parts, const std::vector<int>& weight) {
  const int ne = mesh.num_tets();
  std::vector<int> part(ne, 0);
  if (parts <= 1) return part;
  std::vector<idx_t> eptr(ne + 1), eind(4 * static_cast<size_t>(ne));
  for (int e = 0; e < ne; ++e) {
    eptr[e] = 4 * e;
    for (int a = 0; a < 4; ++a) eind[4 * e + a] = mesh.tets[e][a];
  }
  eptr[ne] = 4 * ne;
  idx_t n_e = ne, n_n = mesh.num_nodes(), ncommon = 3, nparts = parts, objval = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 7;  // the same partition on every rank and every run
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> epart(ne), npart(mesh.num_nodes());
  // Equal weights are no weights: the partition of a one-kind mesh stays METIS's own.
  std::vector<idx_t> vwgt;
  if (!weight.empty() && std::adjacent_find(weight.begin(), weight.end(), std::not_equal_to<>()) != weight.end())
    vwgt.assign(weight.begin(), weight.end());
  const int rc = METIS_PartMeshDual(&n_e, &n_n, eptr.data(), eind.data(), vwgt.empty() ? nullptr : vwgt.data(), nullptr,
                                    &ncommon, &nparts, nullptr, options, &objval, epart.data(),
                                    npart.data());
  std::vector<int> count(parts, 0);
  if (rc == METIS_OK)
    for (int e = 0; e < ne; ++e) part[e] = static_cast<int>(epart[e]), ++count[part[e]];
  // METIS may leave a part empty on tiny meshes; every coordinator must own elements,
  // so fall back to contiguous blocks (compact for structured and Gmsh numberings).
  if (rc != METIS_OK || std::count(count.begin(), count.end(), 0) > 0)
    for (int e = 0; e < ne; ++e) part[e] = static_cast<int>(static_cast<long long>(e) * parts / ne);
  return part;
}

FarmLayout FarmLayout::make(const RunSpec& spec, int ranks, int override_count) {
  FarmLayout L;
  L.ranks = ranks;
  L.coordinators = override_count > 0 ? override_count : spec.farm.coordinators;
  const int ne = spec.mesh.num_tets();
  if (L.coordinators > ranks)
    throw InputError(fmt::format("/farm/coordinators: got {}, expected at most the {} MPI ranks "
                                 "of this launch (or launch more ranks)",
                                 L.coordinators, ranks));
  if (L.coordinators > ne)
    throw InputError(fmt::format("/farm/coordinators: got {}, expected at most the {} macro "
                                 "elements (each coordinator owns at least one)",
                                 L.coordinators, ne));
  for (int r = spec.farm.coordinators_work ? 0 : L.coordinators; r < ranks; ++r)
    L.worker_ranks.push_back(r);
  if (L.worker_ranks.empty())
    throw InputError(fmt::format("/farm/coordinators_work: got false with all {} ranks "
                                 "coordinating, expected at least one worker rank (launch "
                                 "more ranks or let coordinators work)",
                                 ranks));
  // Elements are partitioned, balancing each kind's assembly cost; a point goes with its
  // element (points are numbered wall element after wall element, points_per_element
  // each: MacroPoints).
  L.coordinator_of_element =
      partition_elements(spec.mesh, L.coordinators, scene_fields(spec).element_weights(spec.mesh));
  for (int e : spec.wall_elements())
    L.coordinator_of_unit.insert(L.coordinator_of_unit.end(), static_cast<size_t>(spec.points_per_element),
                                 L.coordinator_of_element[static_cast<size_t>(e)]);
  const int nu = static_cast<int>(L.coordinator_of_unit.size());
  // Macro-law points cost microseconds, less than the ≈ 2 KB messages of a job: by
  // default they stay with their element's coordinator and only FE² units are placed.
  const std::vector<int> model = spec.model_of_points();
  L.local_unit.assign(nu, 0);
  if (spec.farm.macro_law_points == FarmOptions::MacroLawPoints::local)
    for (int u = 0; u < nu; ++u)
      L.local_unit[u] = spec.models[model[u]].kind == PointModelSpec::Kind::macro_law;
  const std::vector<int> farm = L.farm_units();
  const Placement p = static_placement(static_cast<int>(farm.size()),
                                       static_cast<int>(L.worker_ranks.size()), spec.farm.policy);
  L.initial_worker_of_unit = L.coordinator_of_unit;
  for (size_t i = 0; i < farm.size(); ++i)
    L.initial_worker_of_unit[farm[i]] = L.worker_ranks[p.worker_of_unit[i]];
  return L;
}

}  // namespace fe2
