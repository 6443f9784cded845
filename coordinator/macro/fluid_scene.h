#pragma once
// Blood as macro fields (paper Eq. 1, §II-A): the incompressible Navier–Stokes equations
// in ALE form on the fluid regions of the mesh, declared through the field table alone
// (MacroExtension) with their terms, so that the driver solves them in its one Newton
// loop with whatever else the scene has.
//
//   field                   space           time          residual norm
//   fluid_velocity          nodal (P1/P2)   BDF1/BDF2/none ‖R‖/max(‖f_int‖,‖f_ext‖) (reactions included)
//   fluid_pressure          vertex (P1)     none          ‖R‖/‖∫N_p‖: the mean |div v| left
//   fluid_flux_pressure     global, 1/flux face            max |Q_h − Q| / area: a mean normal velocity
//   fluid_pressure_level    global, 1       none          |∫p|/V: the mean pressure (enclosed fluid)
//   mesh_displacement       (optional, read) the ALE map x = X + d, v̂ = its rate
//
// Boundary conditions by face (or node) set, FluidBoundary:
//   velocity   v = g(X, t) on the set's nodes (no-slip: g = 0), chosen components
//   pressure   traction t = −P(t) n (an open boundary), optionally with backflow
//              stabilization β (common/fluid/fluid_boundary.h)
//   flux       ∫(v − v̂)·n da = Q(t), its multiplier λ the face's pressure (a traction
//              −λ n): the form the valve rings take against a circulation model
// Enclosed fluid (no pressure face): the pressure is fixed by ∫p dV = 0 through a
// Lagrange multiplier (fluid_pressure_level), never by pinning a node, so the answer
// does not depend on the numbering; a flux face does not fix it (its multiplier moves
// with the level).
#include "common/fluid/navier_stokes_element.h"
#include "coordinator/macro/MacroPartition.h"
#include "coordinator/macro/MacroTerm.h"
#include "coordinator/macro/macro_scene.h"

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace fe2 {

struct FluidBoundary {
  enum class Kind { velocity, pressure, flux };
  Kind kind = Kind::velocity;
  std::string set;   ///< a node set (velocity) or a face set (pressure, flux)
  /// velocity: the prescribed value at reference point X and time t; components[i]
  /// false leaves component i free (a slip or symmetry plane).
  std::function<Vec3(const Vec3& X, double t)> velocity;
  std::array<bool, 3> components = {true, true, true};
  /// pressure: P(t); flux: Q(t) (volume per time, positive out of the fluid).
  std::function<double(double t)> value;
  double backflow = 0.0;  ///< pressure faces: β of the backflow term (0: off)

  using VelocityValue = std::function<Vec3(const Vec3& X, double t)>;
  using ScalarValue = std::function<double(double t)>;
  static FluidBoundary prescribed_velocity(std::string set, VelocityValue g, std::array<bool, 3> components = {true, true, true}) {
    FluidBoundary b;
    b.set = std::move(set);
    b.velocity = std::move(g);
    b.components = components;
    return b;
  }
  /// v = 0 on the set's nodes (components: a slip plane holds only its normal one).
  static FluidBoundary no_slip(std::string set, std::array<bool, 3> components = {true, true, true}) {
    return prescribed_velocity(std::move(set), [](const Vec3&, double) { return Vec3(Vec3::Zero()); }, components);
  }
  static FluidBoundary pressure(std::string set, ScalarValue P, double backflow = 0.0) {
    FluidBoundary b;
    b.kind = Kind::pressure;
    b.set = std::move(set);
    b.value = std::move(P);
    b.backflow = backflow;
    return b;
  }
  static FluidBoundary flux(std::string set, ScalarValue Q) {
    FluidBoundary b;
    b.kind = Kind::flux;
    b.set = std::move(set);
    b.value = std::move(Q);
    return b;
  }
};

struct FluidSetup {
  std::vector<int> regions;          ///< region tags of the fluid
  NewtonianFluid fluid;
  FluidElementKind element = FluidElementKind::taylor_hood;
  TimeScheme time = TimeScheme::bdf2;///< none: the steady equations
  Vec3 body_force = Vec3::Zero();    ///< per unit mass
  std::vector<FluidBoundary> boundaries;
  double rtol = 1e-8;
  /// No pressure boundary: the pressure level needs its constraint.
  bool enclosed() const;
  /// The flux boundaries' indices into `boundaries`, in order (their multipliers' order).
  std::vector<int> flux_boundaries() const;
};

/// The fluid's fields and its velocity constraints (MacroExtension: add to a scene).
/// Throws fe2::InputError naming the set when a boundary names a set the mesh lacks
/// or the element does not match the mesh's order (Taylor–Hood: quadratic; P1/P1: linear).
MacroExtension fluid_extension(const TetMesh& mesh, const FluidSetup& setup);

/// The fluid's terms over `partition`'s elements of its regions and their faces.
std::vector<std::unique_ptr<MacroTerm>> fluid_terms(const TetMesh& mesh, const FluidSetup& setup,
                                                    const MacroPartition& partition);

}  // namespace fe2
