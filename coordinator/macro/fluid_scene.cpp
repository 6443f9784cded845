#include "coordinator/macro/fluid_scene.h"

#include "common/error.h"
#include "coordinator/macro/FluidBoundaryTerms.h"
#include "coordinator/macro/MeshMotionTerm.h"
#include "coordinator/macro/NavierStokesTerm.h"

#include <algorithm>

namespace fe2 {

bool FluidSetup::enclosed() const {
  return std::none_of(boundaries.begin(), boundaries.end(), [](const FluidBoundary& b) {
    return b.kind == FluidBoundary::Kind::pressure || b.kind == FluidBoundary::Kind::traction;
  });
}

std::vector<int> FluidSetup::flux_boundaries() const {
  std::vector<int> k;
  for (size_t b = 0; b < boundaries.size(); ++b)
    if (boundaries[b].kind == FluidBoundary::Kind::flux) k.push_back(static_cast<int>(b));
  return k;
}

namespace {

void check_setup(const TetMesh& mesh, const FluidSetup& setup) {
  const int order = fluid_velocity_order(setup.element);
  if (mesh.order() != order)
    throw InputError(fmt::format("fluid element {}: needs a {} mesh; this mesh is {}",
                                 order == 2 ? "'taylor_hood' (P2/P1)" : "'p1p1' (stabilized P1/P1)",
                                 order == 2 ? "quadratic" : "linear", mesh.order() == 2 ? "quadratic" : "linear"));
  if (setup.mesh_motion)
    for (const auto& b : setup.mesh_motion->boundaries)
      if (!mesh.node_sets.count(b.set))
        throw InputError(fmt::format("fluid mesh motion boundary: the mesh has no node set '{}'", b.set));
  for (const FluidBoundary& b : setup.boundaries) {
    if (b.kind == FluidBoundary::Kind::moving_wall && !setup.mesh_motion)
      throw InputError(fmt::format("fluid boundary 'moving_wall' on '{}': needs a mesh motion (the wall's velocity "
                                   "is the mesh's); without one use 'no_slip'",
                                   b.set));
    const bool on_faces = b.kind == FluidBoundary::Kind::pressure || b.kind == FluidBoundary::Kind::traction ||
                          b.kind == FluidBoundary::Kind::flux;
    if (on_faces ? !mesh.faces.count(b.set) : !mesh.node_sets.count(b.set))
      throw InputError(fmt::format("fluid boundary: the mesh has no {} '{}'", on_faces ? "face set" : "node set", b.set));
  }
}

}  // namespace

std::vector<int> moving_wall_nodes(const TetMesh& mesh, const FluidSetup& setup) {
  std::vector<char> fluid(static_cast<size_t>(mesh.num_nodes()), 0), taken(fluid.size(), 0), wall(fluid.size(), 0);
  for (int e = 0; e < mesh.num_tets(); ++e)
    if (std::find(setup.regions.begin(), setup.regions.end(), mesh.region[e]) != setup.regions.end())
      for (int a : mesh.element_nodes(e)) fluid[static_cast<size_t>(a)] = 1;
  for (const FluidBoundary& b : setup.boundaries) {
    if (b.kind != FluidBoundary::Kind::velocity && b.kind != FluidBoundary::Kind::moving_wall) continue;
    auto& mark = b.kind == FluidBoundary::Kind::velocity ? taken : wall;
    for (int a : mesh.node_sets.at(b.set)) mark[static_cast<size_t>(a)] = 1;
  }
  std::vector<int> nodes;
  for (int a = 0; a < mesh.num_nodes(); ++a)
    if (wall[static_cast<size_t>(a)] && fluid[static_cast<size_t>(a)] && !taken[static_cast<size_t>(a)]) nodes.push_back(a);
  return nodes;
}

std::vector<std::pair<int, int>> valve_ring_nodes(const TetMesh& mesh, const FluidSetup& setup) {
  std::vector<char> fluid(static_cast<size_t>(mesh.num_nodes()), 0), taken(fluid.size(), 0);
  for (int e = 0; e < mesh.num_tets(); ++e)
    if (std::find(setup.regions.begin(), setup.regions.end(), mesh.region[e]) != setup.regions.end())
      for (int a : mesh.element_nodes(e)) fluid[static_cast<size_t>(a)] = 1;
  for (const FluidBoundary& b : setup.boundaries)
    if (b.kind == FluidBoundary::Kind::velocity || b.kind == FluidBoundary::Kind::moving_wall)
      for (int a : mesh.node_sets.at(b.set)) taken[static_cast<size_t>(a)] = 1;
  std::vector<std::pair<int, int>> nodes;
  int ring = 0;
  for (const FluidBoundary& b : setup.boundaries) {
    if (!b.valve) continue;
    for (int a : mesh.node_sets.at(b.set))
      if (fluid[static_cast<size_t>(a)] && !taken[static_cast<size_t>(a)]) {
        nodes.emplace_back(a, ring);
        taken[static_cast<size_t>(a)] = 1;  // a node on two rings sticks with the first
      }
    ++ring;
  }
  return nodes;
}

MacroExtension fluid_extension(const TetMesh& mesh, const FluidSetup& setup) {
  check_setup(mesh, setup);
  MacroExtension ext;
  ext.fields.push_back({"fluid_velocity", 3, FieldSpace::nodal, setup.regions, 0, setup.time,
                        ResidualNorm::relative_to_load, setup.rtol});
  ext.fields.push_back({"fluid_pressure", 1, FieldSpace::vertex, setup.regions, 0, TimeScheme::none,
                        ResidualNorm::scaled_l2, setup.rtol});
  const int fluxes = static_cast<int>(setup.flux_boundaries().size());
  if (fluxes > 0)
    ext.fields.push_back({"fluid_flux_pressure", 1, FieldSpace::global, {}, fluxes, TimeScheme::none,
                          ResidualNorm::scaled_max, setup.rtol});
  if (const int walls = static_cast<int>(moving_wall_nodes(mesh, setup).size()); walls > 0)
    ext.fields.push_back({"fluid_wall_multiplier", 1, FieldSpace::global, {}, 3 * walls, TimeScheme::none,
                          ResidualNorm::scaled_max, setup.rtol});
  if (const int rings = static_cast<int>(valve_ring_nodes(mesh, setup).size()); rings > 0)
    ext.fields.push_back({"fluid_valve_multiplier", 1, FieldSpace::global, {}, 3 * rings, TimeScheme::none,
                          ResidualNorm::scaled_max, setup.rtol});
  if (setup.mesh_motion)
    ext.fields.push_back({"mesh_displacement", 3, FieldSpace::nodal, setup.regions, 0, setup.time,
                          ResidualNorm::relative_to_load, setup.rtol});
  if (setup.needs_pressure_level())
    ext.fields.push_back({"fluid_pressure_level", 1, FieldSpace::global, {}, 1, TimeScheme::none,
                          ResidualNorm::scaled_max, setup.rtol});
  if (setup.initial_velocity)
    ext.initial = [&mesh, g = setup.initial_velocity](const FieldTable& fields, Eigen::VectorXd& x, Eigen::VectorXd&) {
      const Field& v = fields.at("fluid_velocity");
      for (int a : v.nodes()) x.segment<3>(v.node_dof(a)) = g(mesh.nodes[a]);
    };
  ext.constrain = [&mesh, setup](const FieldTable& fields, MacroConstraints& c) {
    const Field& v = fields.at("fluid_velocity");
    for (const FluidBoundary& b : setup.boundaries) {
      if (b.kind != FluidBoundary::Kind::velocity) continue;
      for (int a : mesh.node_sets.at(b.set)) {
        if (!v.has_node(a)) continue;  // a set reaching past the fluid
        const Vec3 X = mesh.nodes[a];
        for (int i = 0; i < 3; ++i)
          if (b.components[i]) c.prescribe(v.node_dof(a, i), c.add_value([g = b.velocity, X, i](double t) { return g(X, t)[i]; }));
      }
    }
    if (!setup.mesh_motion) return;
    const Field& d = fields.at("mesh_displacement");
    const Field& u = fields.at("displacement");
    for (const auto& b : setup.mesh_motion->boundaries)
      for (int a : mesh.node_sets.at(b.set)) {
        if (!d.has_node(a)) continue;
        const Vec3 X = mesh.nodes[a];
        for (int i = 0; i < 3; ++i) {
          if (b.displacement)
            c.prescribe(d.node_dof(a, i), c.add_value([g = b.displacement, X, i](double t) { return g(X, t)[i]; }));
          else if (u.has_node(a))
            c.follow(d.node_dof(a, i), u.node_dof(a, i));
        }
      }
  };
  return ext;
}

namespace {

/// Q(t) of a flux boundary: its value, or its valve's flow at the circulation's last
/// assembly (zero before the first).
std::function<double(double)> flux_of(const FluidBoundary& b, const CavityPressureTerm* cavities) {
  if (!b.valve) return b.value;
  const FluidBoundary::Valve valve = *b.valve;
  return [cavities, valve](double) {
    const CavityFlows& f = cavities->flows();
    if (valve.cavity >= f.n) return 0.0;
    const size_t c = static_cast<size_t>(valve.cavity);
    return valve.outflow ? f.Q_out[c] : -f.Q_in[c];
  };
}

/// The valve rings' states from the circulation's valves (open: Δp > 0 across it).
std::shared_ptr<ValveStates> valve_states(const FluidSetup& setup, const CavityPressureTerm* cavities) {
  std::vector<FluidBoundary::Valve> valves;
  for (const FluidBoundary& b : setup.boundaries) {
    if (!b.valve) continue;
    if (!cavities)
      throw InputError(fmt::format("fluid valve ring '{}': needs a circulation (the flow through the valve)", b.set));
    valves.push_back(*b.valve);
  }
  if (valves.empty()) return nullptr;
  return std::make_shared<ValveStates>([cavities, valves] {
    const CavityFlows& f = cavities->flows();
    std::vector<bool> open;
    for (const FluidBoundary::Valve& v : valves) {
      const size_t c = static_cast<size_t>(v.cavity);
      open.push_back(v.cavity < f.n && (v.outflow ? f.outflow_open[c] : f.inflow_open[c]));
    }
    return open;
  });
}

/// A two-way ring's Q(p_c) derivatives, or (inflow ring, wall inflating) the cavity
/// pressure it holds.
std::function<FluxConstraintTerm::RingCoupling()> ring_coupling(const FluidBoundary::Valve& valve,
                                                                 const CavityPressureTerm& cavities) {
  return [valve, &cavities] {
    FluxConstraintTerm::RingCoupling rc;
    const size_t n = static_cast<size_t>(cavities.count());
    if (cavities.inflating()) {
      if (!valve.outflow) rc.holds_pressure_of = valve.cavity;
      return rc;
    }
    const std::vector<double>& dQ = valve.outflow ? cavities.flows().dQout_dp : cavities.flows().dQin_dp;
    // Q of an inflow ring is −Q_in (out of the fluid).
    const double sign = valve.outflow ? 1.0 : -1.0;
    for (size_t j = 0; j < n; ++j) rc.dQ_dp.push_back(sign * dQ[static_cast<size_t>(valve.cavity) * n + j]);
    return rc;
  };
}

}  // namespace

std::vector<std::unique_ptr<MacroTerm>> fluid_terms(const TetMesh& mesh, const FluidSetup& setup,
                                                    const MacroPartition& partition,
                                                    CavityPressureTerm* cavities) {
  std::vector<int> elements;
  for (int e : partition.elements())
    if (std::find(setup.regions.begin(), setup.regions.end(), mesh.region[e]) != setup.regions.end())
      elements.push_back(e);
  std::vector<std::unique_ptr<MacroTerm>> terms;
  terms.push_back(std::make_unique<NavierStokesTerm>(mesh, elements, setup.element, setup.fluid, setup.body_force,
                                                     setup.residual_pressure, setup.shape_derivatives));
  std::vector<OpenBoundaryTerm::Boundary> open;
  std::vector<FluxConstraintTerm::Boundary> flux;
  const std::shared_ptr<ValveStates> valves = valve_states(setup, cavities);
  int ring = 0;
  for (const FluidBoundary& b : setup.boundaries) {
    if (b.kind == FluidBoundary::Kind::pressure) open.push_back({b.set, b.value, b.backflow, {}});
    if (b.kind == FluidBoundary::Kind::traction) open.push_back({b.set, {}, b.backflow, b.traction});
    if (b.kind != FluidBoundary::Kind::flux) continue;
    std::function<bool()> active;
    if (b.valve) active = [valves, k = ring++] { return valves->open(k); };
    std::function<FluxConstraintTerm::RingCoupling()> coupling;
    if (b.valve && setup.two_way && cavities) coupling = ring_coupling(*b.valve, *cavities);
    flux.push_back({b.set, flux_of(b, cavities), active, coupling});
  }
  // Two-way, the circulation shuts what the rings hold shut (what leaves the cavity is
  // what they pass).
  if (valves && setup.two_way && cavities) {
    std::vector<FluidBoundary::Valve> rings;
    for (const FluidBoundary& b : setup.boundaries)
      if (b.valve) rings.push_back(*b.valve);
    cavities->hold_valves([valves, rings, n = static_cast<size_t>(cavities->count())] {
      Circulation::HeldShut held;
      if (!valves->holding()) return held;
      held.inflow.assign(n, false);
      held.outflow.assign(n, false);
      for (size_t k = 0; k < rings.size(); ++k)
        if (!valves->open(static_cast<int>(k))) (rings[k].outflow ? held.outflow : held.inflow)[static_cast<size_t>(rings[k].cavity)] = true;
      return held;
    });
  }
  // The valve closure updates the valves' states: before the rings' flux rows.
  if (const auto rings = valve_ring_nodes(mesh, setup); !rings.empty()) {
    std::vector<int> nodes, ring_of_node;
    for (const auto& [a, k] : rings) nodes.push_back(a), ring_of_node.push_back(k);
    terms.push_back(std::make_unique<MovingWallTerm>(partition, std::move(nodes), "fluid_valve_multiplier", valves,
                                                     std::move(ring_of_node)));
  }
  if (!open.empty()) terms.push_back(std::make_unique<OpenBoundaryTerm>(mesh, partition, setup.regions, open, setup.fluid.density));
  if (!flux.empty()) terms.push_back(std::make_unique<FluxConstraintTerm>(mesh, partition, setup.regions, flux));
  if (setup.needs_pressure_level()) terms.push_back(std::make_unique<PressureLevelTerm>(mesh, elements));
  if (std::vector<int> walls = moving_wall_nodes(mesh, setup); !walls.empty())
    terms.push_back(setup.two_way ? MovingWallTerm::loading_wall(partition, std::move(walls))
                                  : std::make_unique<MovingWallTerm>(partition, std::move(walls)));
  if (setup.mesh_motion)
    terms.push_back(std::make_unique<MeshMotionTerm>(mesh, elements, setup.mesh_motion->kind,
                                                     setup.mesh_motion->stiffening));
  return terms;
}

}  // namespace fe2
