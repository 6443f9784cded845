#pragma once
// Follower pressure t = −p n on the deformed surface (/pressure loads; p > 0 pushes
// against the outward normal of the solid, i.e. into it):
//   f_ext,a = −p ∫ N_a (∂x/∂ξ₁ × ∂x/∂ξ₂) dξ over linear or 6-node triangles
// (common/fem/follower_pressure.h), with its unsymmetric consistent tangent.
#include "coordinator/RunSpec.h"
#include "coordinator/macro/MacroPartition.h"
#include "coordinator/macro/MacroTerm.h"

namespace fe2 {

class FollowerPressureTerm final : public MacroTerm {
 public:
  /// The triangles of every /pressure load that bound the partition's elements.
  FollowerPressureTerm(const RunSpec& spec, const MacroPartition& partition);
  std::string name() const override { return "follower pressure"; }
  void declare(MacroSystem& system) override;
  void assemble(const MacroState& state, MacroAssembly& out) override;

 private:
  const RunSpec& spec_;
  struct Face {
    std::vector<int> nodes;
    int load;
  };
  std::vector<Face> faces_;
  const Field* u_ = nullptr;
  std::vector<int> local_;
  std::vector<std::vector<int>> dofs_;
};

}  // namespace fe2
