#pragma once
// What a scene's blood is (fluid_scene.h builds its fields and terms from it): regions,
// fluid, element, time scheme, boundary conditions by set, the mesh's motion. Read from
// the spec's "fluid" section (coordinator/fluid_spec.h) or built in code (tests).
#include "common/fluid/navier_stokes_element.h"
#include "coordinator/macro/FieldTable.h"

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace fe2 {

/// How the mesh displacement extends its boundary values (MeshMotionTerm.h).
enum class MeshMotionKind { harmonic, elastic };

struct FluidBoundary {
  /// moving_wall: v = v̂ (the mesh velocity) on the set's nodes, by multipliers: no-slip
  /// on a wall that moves with the mesh (nodes under a velocity condition keep that).
  enum class Kind { velocity, pressure, traction, flux, moving_wall };
  Kind kind = Kind::velocity;
  std::string set;   ///< a node set (velocity) or a face set (pressure, flux)
  /// velocity: the prescribed value at reference point X and time t; components[i]
  /// false leaves component i free (a slip or symmetry plane).
  std::function<Vec3(const Vec3& X, double t)> velocity;
  std::array<bool, 3> components = {true, true, true};
  /// pressure: P(t); flux: Q(t) (volume per time, positive out of the fluid).
  std::function<double(double t)> value;
  /// flux through a valve ring: Q is the circulation's flow through a cavity's valve at
  /// the current iterate (out of the fluid: +Q_out of the outflow valve, −Q_in of the
  /// inflow one) in place of `value`. One-way: the circulation sees the wall's cavity
  /// pressure, not the ring's (issue 31 closes that loop).
  struct Valve {
    int cavity = 0;        ///< index into the circulation's cavities
    bool outflow = true;   ///< the outflow (aortic) or inflow (mitral) valve
  };
  std::optional<Valve> valve;
  /// traction: t(t), the force per current area the outside exerts on the blood.
  std::function<Vec3(double t)> traction;
  double backflow = 0.0;  ///< pressure, traction, flux and valve faces: β of the backflow term (0: off)

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
  static FluidBoundary traction_of(std::string set, std::function<Vec3(double)> t, double backflow = 0.0) {
    FluidBoundary b;
    b.kind = Kind::traction;
    b.set = std::move(set);
    b.traction = std::move(t);
    b.backflow = backflow;
    return b;
  }
  static FluidBoundary moving_wall(std::string set) {
    FluidBoundary b;
    b.kind = Kind::moving_wall;
    b.set = std::move(set);
    return b;
  }
  static FluidBoundary flux(std::string set, ScalarValue Q, double backflow = 0.0) {
    FluidBoundary b;
    b.kind = Kind::flux;
    b.set = std::move(set);
    b.value = std::move(Q);
    b.backflow = backflow;
    return b;
  }
  static FluidBoundary valve_flux(std::string set, Valve valve, double backflow = 0.0) {
    FluidBoundary b;
    b.kind = Kind::flux;
    b.set = std::move(set);
    b.valve = valve;
    b.backflow = backflow;
    return b;
  }
};

/// The fluid mesh's motion (MeshMotionTerm.h): the mesh_displacement field on the fluid,
/// moved by its boundary.
struct MeshMotionSetup {
  MeshMotionKind kind = MeshMotionKind::harmonic;
  double stiffening = 1.0;  ///< χ of s_e = (V̄/V_e)^χ
  struct Boundary {
    std::string set;  ///< a node set
    /// d(X, t) on the set's fluid nodes; empty: follow the wall's displacement there
    /// (the set's nodes shared with the wall).
    std::function<Vec3(const Vec3& X, double t)> displacement;
  };
  std::vector<Boundary> boundaries;
};

struct FluidSetup {
  std::vector<int> regions;          ///< region tags of the fluid
  NewtonianFluid fluid;
  FluidElementKind element = FluidElementKind::taylor_hood;
  ConvectiveForm convection = ConvectiveForm::advective;
  TimeScheme time = TimeScheme::bdf2;///< none: the steady equations
  Vec3 body_force = Vec3::Zero();    ///< per unit mass
  std::vector<FluidBoundary> boundaries;
  std::optional<MeshMotionSetup> mesh_motion;  ///< none: a fixed (Eulerian) fluid mesh
  /// The moving walls' multipliers (the force the wall exerts on the blood) act back on
  /// the wall's displacement equations: R_u,a −= λ_a (fluid_scene.h).
  bool two_way = false;
  /// The blood's tangent with respect to the mesh motion (NavierStokesTerm.h); the
  /// reader turns it on with two_way, where the wall's convergence needs it.
  bool shape_derivatives = false;
  /// The velocity at t_start at reference point X (empty: at rest).
  std::function<Vec3(const Vec3& X)> initial_velocity;
  double rtol = 1e-8;
  /// The pressure whose nodal forces floor the momentum residual's reference: below
  /// rtol times these the flow is converged even when every force vanishes.
  double residual_pressure = 1.0;
  /// No pressure or traction boundary.
  bool enclosed() const;
  /// Enclosed and one-way: nothing sets the pressure level but its constraint (two-way,
  /// the wall's compliance and the rings' valve laws set it).
  bool needs_pressure_level() const { return enclosed() && !two_way; }
  /// The flux boundaries' indices into `boundaries`, in order (their multipliers' order).
  std::vector<int> flux_boundaries() const;
};

}  // namespace fe2
