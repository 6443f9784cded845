#pragma once
// The fluid's volume term: common/fluid/navier_stokes_element.h on every fluid element
// of the partition, on the current ALE geometry x = X + d (d the mesh_displacement field
// when the scene has one, else 0) with the mesh velocity v̂ = ḋ, and the field's rate
// ∂v/∂t|_χ from its time scheme.
//
// Shape derivatives (`shape_derivatives`, on when the blood loads the wall: two-way
// coupling): the residual depends on the mesh motion d through the geometry x = X + d
// and the mesh velocity v̂ = ḋ, so with d following the wall the tangent needs
//   ∂R_e/∂d_b = ∂R_e/∂x_b + (∂ḋ/∂d) ∂R_e/∂v̂_b
// (the blood's pressure on a moving wall is a follower load: without this block Newton
// loses the load stiffness and, on a soft wall, diverges). Analytic, from the element
// (navier_stokes_element's K_x, every term of every element kind): exact, where forward
// differences were good to ~1e-7 and cost 3n residual evaluations per element.
#include "common/fluid/navier_stokes_element.h"
#include "common/mesh/TetMesh.h"
#include "coordinator/macro/MacroTerm.h"

namespace fe2 {

class NavierStokesTerm final : public MacroTerm {
 public:
  /// `residual_pressure`: the pressure whose nodal forces floor the momentum residual's
  /// reference (a flow whose forces all vanish, at rest or uniform, still converges).
  NavierStokesTerm(const TetMesh& mesh, std::vector<int> elements, FluidElementKind kind, ConvectiveForm convection,
                   NewtonianFluid fluid, Vec3 body_force, double residual_pressure, bool shape_derivatives = false);
  std::string name() const override { return "navier-stokes"; }
  Physics physics() const override { return Physics::fluid; }
  void declare(MacroSystem& system) override;
  /// ∫ N_p dV per pressure DOF: the continuity residual's scale (a mean |div v|); and
  /// P_ref ∫ |∂N_a/∂x_i| dV per velocity DOF: the momentum residual's floor.
  void add_residual_scale(const Field& field, Eigen::VectorXd& scale) const override;
  void assemble(const MacroState& state, MacroAssembly& out) override;
  /// fluid_volume (current), fluid_kinetic_energy ½ρ∫|v|² and fluid_dissipation_rate ∫2μ ε:ε.
  void observe(const MacroState& state, std::vector<Observable>& out) const override;

 private:
  /// Element k's geometry and nodal fields at `state` (s's data; its scheme's scalars kept).
  void gather_element(size_t k, const MacroState& state, FluidElementState& s) const;
  const TetMesh& mesh_;
  std::vector<int> elements_;
  FluidElementKind kind_;
  ConvectiveForm convection_;
  NewtonianFluid fluid_;
  Vec3 body_force_;
  double residual_pressure_;
  bool shape_derivatives_;
  const Field *v_ = nullptr, *p_ = nullptr, *d_ = nullptr;
  std::vector<std::vector<int>> nodes_, dofs_;  ///< per element: its nodes; its v then p DOFs
  std::vector<int> local_;
  std::vector<std::vector<int>> mesh_dofs_;  ///< shape derivatives: per element, d's DOFs (3 per node)
};

}  // namespace fe2
