#pragma once
// Blood as macro fields (paper Eq. 1, §II-A): the incompressible Navier–Stokes equations
// in ALE form on the fluid regions of the mesh, declared through the field table alone
// (MacroExtension) with their terms, so that the driver solves them in its one Newton
// loop with whatever else the scene has.
//
//   field                   space           time          residual norm
//   fluid_velocity          nodal (P1/P2)   BDF1/BDF2/none ‖R‖/max(‖f_int‖,‖f_ext‖,‖s‖) (reactions
//                                                         included; s: residual_pressure's nodal forces)
//   fluid_pressure          vertex (P1)     none          ‖R‖/‖∫N_p‖: the mean |div v| left
//   fluid_flux_pressure     global, 1/flux face            max |Q_h − Q| / area: a mean normal velocity
//   fluid_pressure_level    global, 1       none          |∫p|/V: the mean pressure (enclosed fluid)
//   fluid_wall_multiplier   global, 3/node  none          max |v − v̂| on moving walls (velocity units)
//   fluid_valve_multiplier  global, 3/node  none          the same on the rings of shut valves
//   mesh_displacement       nodal, when the mesh moves: the ALE map x = X + d, v̂ = ḋ by
//                           the fluid's time scheme (MeshMotionTerm.h)
//
// Boundary conditions by face (or node) set, FluidBoundary:
//   velocity   v = g(X, t) on the set's nodes (no-slip: g = 0), chosen components
//   pressure   traction t = −P(t) n (an open boundary), optionally with backflow
//              stabilization β (common/fluid/fluid_boundary.h)
//   flux       ∫(v − v̂)·n da = Q(t), its multiplier λ the face's pressure (a traction
//              −λ n): the form the valve rings take against a circulation model
//   valve      a flux face whose Q is the circulation's flow through a cavity's valve
//              (FluidBoundary::Valve) while that valve is open; while it is shut the
//              ring's nodes stick (v = v̂) and λ = 0. The state is held for a step.
//   moving_wall v = v̂ at the set's nodes (those not under a velocity condition), by a
//              multiplier per node and component: the force the wall exerts on the blood;
//              with `coupling: two_way` its opposite loads the wall at the shared node
//              (one Newton loop over wall and blood: the monolithic FSI of paper §II-A)
// Enclosed fluid (no pressure face): the pressure is fixed by ∫p dV = 0 through a
// Lagrange multiplier (fluid_pressure_level), never by pinning a node, so the answer
// does not depend on the numbering; a flux face does not fix it (its multiplier moves
// with the level).
#include "coordinator/macro/CavityPressureTerm.h"
#include "coordinator/macro/FluidSetup.h"
#include "coordinator/macro/MacroPartition.h"
#include "coordinator/macro/MacroTerm.h"
#include "coordinator/macro/macro_scene.h"

#include <memory>
#include <vector>

namespace fe2 {

/// The fluid's fields and its velocity constraints (MacroExtension: add to a scene).
/// Throws fe2::InputError naming the set when a boundary names a set the mesh lacks
/// or the element does not match the mesh's order (Taylor–Hood: quadratic; P1/P1: linear).
MacroExtension fluid_extension(const TetMesh& mesh, const FluidSetup& setup);

/// The setup's checks against its mesh (the element's order, the sets, a flux face or
/// valve ring with a node of its own); throws InputError naming the boundary.
void check_fluid_setup(const TetMesh& mesh, const FluidSetup& setup);

/// The fluid's nodes of its moving_wall sets that no velocity condition prescribes,
/// ascending: the nodes where v = v̂ is imposed.
std::vector<int> moving_wall_nodes(const TetMesh& mesh, const FluidSetup& setup);

/// The fluid's nodes of its valve rings that no velocity or moving-wall condition
/// holds, ascending, each with the rings (indices among the valve boundaries) it is on:
/// where a shut valve sticks (a node two rings share sticks while either is shut).
std::vector<std::pair<int, std::vector<int>>> valve_ring_nodes(const TetMesh& mesh, const FluidSetup& setup);

/// The fluid's terms over `partition`'s elements of its regions and their faces;
/// `cavities`: the circulation's term, whose valve flows drive valve rings (assembled
/// before these terms, so its flows are the current iterate's).
std::vector<std::unique_ptr<MacroTerm>> fluid_terms(const TetMesh& mesh, const FluidSetup& setup,
                                                    const MacroPartition& partition,
                                                    CavityPressureTerm* cavities = nullptr);

}  // namespace fe2
