#pragma once
// The fluid mesh follows its boundary (paper §II-A: the ALE map): the mesh displacement d
// solves, on the reference fluid mesh, a linear extension of its boundary values
//   harmonic   ∫ s_e ∇w : ∇d dV = 0                       (each component Laplace)
//   elastic    ∫ s_e (2 ε(w):ε(d) + λ' div w div d) dV = 0 (λ' = 2ν/(1 − 2ν), ν = 0.3)
// with Jacobian-based stiffening s_e = (V̄/V_e)^χ (Stein, Tezduyar & Benney 2003, J Appl
// Mech 70:58; V̄ the fluid's mean element volume): small elements, near the moving walls
// where they are smallest, are stiffer and deform less. χ = 0 is the plain extension.
// Linear in d: its block is constant, its residual K d. Its boundary values are
// constraints (prescribed, or following the wall displacement on shared nodes).
//
// The term also watches the moved mesh: every step it reports the worst fluid element's
// shape (η = 6√2 V/l_rms³ of the current vertex tet, element_quality.h) as the
// observable fluid_mesh_worst_shape. An inverted fluid element is a NumericalError of
// the fluid element itself (the step is cut back).
#include "common/mesh/TetMesh.h"
#include "coordinator/macro/FluidSetup.h"
#include "coordinator/macro/MacroTerm.h"

namespace fe2 {

class MeshMotionTerm final : public MacroTerm {
 public:
  MeshMotionTerm(const TetMesh& mesh, std::vector<int> elements, MeshMotionKind kind, double stiffening);
  std::string name() const override { return "mesh motion"; }
  Physics physics() const override { return Physics::fluid; }
  void declare(MacroSystem& system) override;
  void assemble(const MacroState& state, MacroAssembly& out) override;
  /// fluid_mesh_worst_shape: the worst current η over the fluid's elements (1 for a
  /// regular tet, ≤ 0 inverted).
  void observe(const MacroState& state, std::vector<Observable>& out) const override;

 private:
  const TetMesh& mesh_;
  std::vector<int> elements_;
  MeshMotionKind kind_;
  double stiffening_;
  const Field* d_ = nullptr;
  std::vector<std::vector<int>> dofs_;
  std::vector<Eigen::MatrixXd> stiffness_;
  std::vector<int> local_;
};

}  // namespace fe2
