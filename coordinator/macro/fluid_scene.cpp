#include "coordinator/macro/fluid_scene.h"

#include "common/error.h"
#include "coordinator/macro/FluidBoundaryTerms.h"
#include "coordinator/macro/MeshMotionTerm.h"
#include "coordinator/macro/NavierStokesTerm.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <map>
#include <limits>

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

/// Per mesh node: whether a fluid element has it.
std::vector<char> fluid_nodes(const TetMesh& mesh, const FluidSetup& setup) {
  std::vector<char> fluid(static_cast<size_t>(mesh.num_nodes()), 0);
  for (int e = 0; e < mesh.num_tets(); ++e)
    if (std::find(setup.regions.begin(), setup.regions.end(), mesh.region[e]) != setup.regions.end())
      for (int a : mesh.element_nodes(e)) fluid[static_cast<size_t>(a)] = 1;
  return fluid;
}

/// Per mesh node: whether a boundary of `kind` holds it (`every_component`: in all three
/// components).
std::vector<char> nodes_of(const TetMesh& mesh, const FluidSetup& setup, FluidBoundary::Kind kind,
                           bool every_component = false) {
  std::vector<char> on(static_cast<size_t>(mesh.num_nodes()), 0);
  for (const FluidBoundary& b : setup.boundaries)
    if (b.kind == kind && (!every_component || (b.components[0] && b.components[1] && b.components[2])))
      for (int a : mesh.node_sets.at(b.set)) on[static_cast<size_t>(a)] = 1;
  return on;
}

}  // namespace

void check_fluid_setup(const TetMesh& mesh, const FluidSetup& setup) {
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
  // A flux face whose every node another condition holds passes nothing, whatever its
  // pressure (a ring of one coarse triangle inside a no-slip cap).
  const std::vector<char> velocity = nodes_of(mesh, setup, FluidBoundary::Kind::velocity, true);
  const std::vector<char> wall = nodes_of(mesh, setup, FluidBoundary::Kind::moving_wall);
  for (size_t k = 0; k < setup.boundaries.size(); ++k) {
    const FluidBoundary& b = setup.boundaries[k];
    if (b.kind != FluidBoundary::Kind::flux) continue;
    bool free = false;
    for (const auto& tri : mesh.faces.at(b.set))
      for (int a : mesh.face_nodes(tri)) free = free || !(velocity[static_cast<size_t>(a)] || wall[static_cast<size_t>(a)]);
    if (!free)
      throw InputError(fmt::format("/fluid/boundaries/{}/set: '{}' ({}): every node of its faces is held by a velocity, "
                                   "no_slip or moving_wall set, so no blood can pass it; expected nodes of its own (a "
                                   "finer mesh there, or a wider ring)",
                                   k, b.set, b.valve ? "a valve ring" : "a flux face"));
  }
}

std::vector<int> moving_wall_nodes(const TetMesh& mesh, const FluidSetup& setup) {
  const std::vector<char> fluid = fluid_nodes(mesh, setup);
  const std::vector<char> taken = nodes_of(mesh, setup, FluidBoundary::Kind::velocity);
  const std::vector<char> wall = nodes_of(mesh, setup, FluidBoundary::Kind::moving_wall);
  std::vector<int> nodes;
  for (size_t a = 0; a < fluid.size(); ++a)
    if (wall[a] && fluid[a] && !taken[a]) nodes.push_back(static_cast<int>(a));
  return nodes;
}

std::vector<std::pair<int, std::vector<int>>> valve_ring_nodes(const TetMesh& mesh, const FluidSetup& setup) {
  const std::vector<char> fluid = fluid_nodes(mesh, setup);
  const std::vector<char> velocity = nodes_of(mesh, setup, FluidBoundary::Kind::velocity);
  const std::vector<char> wall = nodes_of(mesh, setup, FluidBoundary::Kind::moving_wall);
  std::map<int, std::vector<int>> rings_of_node;
  int ring = 0;
  for (const FluidBoundary& b : setup.boundaries) {
    if (!b.valve) continue;
    for (int a : mesh.node_sets.at(b.set))
      if (fluid[static_cast<size_t>(a)] && !velocity[static_cast<size_t>(a)] && !wall[static_cast<size_t>(a)])
        rings_of_node[a].push_back(ring);
    ++ring;
  }
  return {rings_of_node.begin(), rings_of_node.end()};
}

MacroExtension fluid_extension(const TetMesh& mesh, const FluidSetup& setup) {
  check_fluid_setup(mesh, setup);
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

/// The valve rings' states from the circulation's valves: a shut ring opens when the
/// pressure drop across its valve with the cavity at p_c is positive; an open ring stays
/// open while its valve passes blood forward (Δp > 0 across it); while the wall is inflated
/// the inflow ring is open. One-way, the states follow the iterate during a step's first
/// iterations. Two-way they are held for whole steps and checked at convergence
/// (ValveStates::accept): with the ring's pressure an unknown, a state decided from an
/// unconverged iterate chatters; and an open ring shuts only once blood flows back through
/// its valve (Δp below minus the valve's width at the ring's pressure), since a valve
/// open at Δp ≈ 0 passes nothing and is as consistent as a shut one.
std::shared_ptr<ValveStates> valve_states(const FluidSetup& setup, const CavityPressureTerm* cavities) {
  std::vector<FluidBoundary::Valve> valves;
  for (const FluidBoundary& b : setup.boundaries) {
    if (!b.valve) continue;
    if (!cavities)
      throw InputError(fmt::format("fluid valve ring '{}': needs a circulation (the flow through the valve)", b.set));
    valves.push_back(*b.valve);
  }
  if (valves.empty()) return nullptr;
  const bool held_for_steps = setup.two_way;
  return std::make_shared<ValveStates>([cavities, valves, held_for_steps](const std::vector<bool>& previous) {
    const CavityFlows& f = cavities->flows();
    std::vector<bool> open;
    for (size_t k = 0; k < valves.size(); ++k) {
      const FluidBoundary::Valve& v = valves[k];
      const size_t c = static_cast<size_t>(v.cavity);
      if (v.cavity >= f.n) {
        open.push_back(false);
        continue;
      }
      const bool passes = v.outflow ? f.outflow_open[c] : f.inflow_open[c];
      const bool stays = held_for_steps ? !(v.outflow ? f.outflow_reversed[c] : f.inflow_reversed[c]) : passes;
      const bool opens = (v.outflow ? f.outflow_drop[c] : f.inflow_drop[c]) > 0.0;
      open.push_back(previous.empty() || f.phase[c] == "inflation" ? passes : previous[k] ? stays : opens);
      if (!previous.empty() && previous[k] != open.back())
        spdlog::debug("valve ring {} of cavity {}: {} (Δp {:.6g} Pa across the valve at p_c; Q {:.6g} mm³/s)",
                      v.outflow ? "outflow" : "inflow", v.cavity, open.back() ? "opens" : "shuts",
                      v.outflow ? f.outflow_drop[c] : f.inflow_drop[c], v.outflow ? f.Q_out[c] : f.Q_in[c]);
    }
    return open;
  }, setup.two_way ? 0 : 5);
}

/// A two-way ring's coupling to the circulation (FluxConstraintTerm::RingCoupling): open,
/// the derivatives of its valve's flow; shut, or the inflow ring while the wall is
/// inflated, it holds the cavity's pressure. `port_of_flux`: per flux boundary, the
/// column of its ring pressure among CavityFlows::dQin_dport's, or −1.
std::function<FluxConstraintTerm::RingCoupling()> ring_coupling(const FluidBoundary::Valve& valve, int ring,
                                                                 const CavityPressureTerm& cavities,
                                                                 std::shared_ptr<ValveStates> valves,
                                                                 std::vector<int> port_of_flux) {
  return [valve, ring, &cavities, valves, port_of_flux] {
    FluxConstraintTerm::RingCoupling rc;
    if ((cavities.inflating() && !valve.outflow) || !valves->open(ring)) {
      rc.holds_pressure_of = valve.cavity;
      return rc;
    }
    const size_t n = static_cast<size_t>(cavities.count()), c = static_cast<size_t>(valve.cavity);
    const CavityFlows& f = cavities.flows();
    const std::vector<double>& dQ = valve.outflow ? f.dQout_dp : f.dQin_dp;
    const std::vector<double>& dQ_dport = valve.outflow ? f.dQout_dport : f.dQin_dport;
    // Q of an inflow ring is −Q_in (out of the fluid).
    const double sign = valve.outflow ? 1.0 : -1.0;
    for (size_t j = 0; j < n; ++j) rc.dQ_dp.push_back(sign * dQ[c * n + j]);
    for (const int column : port_of_flux)
      rc.dQ_dring.push_back(column < 0 ? 0.0 : sign * dQ_dport[c * 2 * n + static_cast<size_t>(column)]);
    return rc;
  };
}

/// The rings' ports for the circulation (Circulation::ValvePorts) from their pressures:
/// a shut ring's valve is held shut, an open one sees its ring's pressure. The rings'
/// states are updated here, once per assembly, before the circulation is evaluated.
CavityPressureTerm::RingPorts ring_ports(std::shared_ptr<ValveStates> valves, std::vector<FluidBoundary::Valve> rings,
                                         std::vector<int> flux_of_ring, int cavities) {
  valves->update_before_circulation();
  return [valves, rings, flux_of_ring, n = static_cast<size_t>(cavities)](std::span<const double> lambda) {
    valves->update();  // from the last evaluation's flows: the previous iterate
    Circulation::ValvePorts ports;
    ports.inflow_shut.assign(n, false);
    ports.outflow_shut.assign(n, false);
    ports.inflow_pressure.assign(n, std::numeric_limits<double>::quiet_NaN());
    ports.outflow_pressure.assign(n, std::numeric_limits<double>::quiet_NaN());
    for (size_t k = 0; k < rings.size(); ++k) {
      const size_t c = static_cast<size_t>(rings[k].cavity);
      if (!valves->open(static_cast<int>(k))) (rings[k].outflow ? ports.outflow_shut : ports.inflow_shut)[c] = true;
      else (rings[k].outflow ? ports.outflow_pressure : ports.inflow_pressure)[c] = lambda[static_cast<size_t>(flux_of_ring[k])];
    }
    return ports;
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
  terms.push_back(std::make_unique<NavierStokesTerm>(mesh, elements, setup.element, setup.convection, setup.fluid,
                                                     setup.body_force, setup.residual_pressure,
                                                     setup.shape_derivatives));
  std::vector<OpenBoundaryTerm::Boundary> open;
  std::vector<FluxConstraintTerm::Boundary> flux;
  const std::shared_ptr<ValveStates> valves = valve_states(setup, cavities);
  const bool two_way_rings = valves && setup.two_way && cavities;
  // Per flux boundary, its ring pressure's column among the circulation's ports; per
  // ring, its flux boundary.
  std::vector<int> port_of_flux, flux_of_ring;
  std::vector<FluidBoundary::Valve> rings;
  for (const FluidBoundary& b : setup.boundaries) {
    if (b.kind != FluidBoundary::Kind::flux) continue;
    if (b.valve) {
      flux_of_ring.push_back(static_cast<int>(port_of_flux.size()));
      rings.push_back(*b.valve);
    }
    port_of_flux.push_back(!b.valve || !cavities ? -1
                           : b.valve->outflow    ? cavities->count() + b.valve->cavity
                                                 : b.valve->cavity);
  }
  int ring = 0;
  for (const FluidBoundary& b : setup.boundaries) {
    if (b.kind == FluidBoundary::Kind::pressure) open.push_back({b.set, b.value, b.backflow, {}});
    if (b.kind == FluidBoundary::Kind::traction) open.push_back({b.set, {}, b.backflow, b.traction});
    if (b.kind != FluidBoundary::Kind::flux) continue;
    std::function<bool()> active;
    std::function<FluxConstraintTerm::RingCoupling()> coupling;
    if (b.valve) {
      active = [valves, k = ring] { return valves->open(k); };
      if (two_way_rings) coupling = ring_coupling(*b.valve, ring, *cavities, valves, port_of_flux);
      ++ring;
    }
    flux.push_back({b.set, flux_of(b, cavities), active, coupling, b.backflow, setup.fluid.density});
  }
  // Two-way, the circulation's valves meet the rings: shut where they are shut, driven by
  // the ring's pressure where they are open.
  if (two_way_rings) cavities->couple_rings(ring_ports(valves, rings, flux_of_ring, cavities->count()));
  // The valve closure updates the valves' states: before the rings' flux rows.
  if (const auto rings = valve_ring_nodes(mesh, setup); !rings.empty()) {
    std::vector<int> nodes;
    std::vector<std::vector<int>> ring_of_node;
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
