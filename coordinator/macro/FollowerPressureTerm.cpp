#include "coordinator/macro/FollowerPressureTerm.h"

#include "common/fem/follower_pressure.h"

namespace fe2 {

FollowerPressureTerm::FollowerPressureTerm(const RunSpec& spec, const MacroPartition& partition) : spec_(spec) {
  for (size_t p = 0; p < spec.pressure.size(); ++p)
    for (const auto& tri : partition.owned_faces(spec.mesh, spec.mesh.faces.at(spec.pressure[p].surface)))
      faces_.push_back({spec.mesh.face_nodes(tri), static_cast<int>(p)});
}

void FollowerPressureTerm::declare(MacroSystem& system) {
  u_ = &system.field("displacement");
  for (const Face& f : faces_) {
    dofs_.push_back(u_->node_dofs(f.nodes));
    local_.push_back(system.declare_local(dofs_.back()));
  }
}

void FollowerPressureTerm::assemble(const MacroState& state, MacroAssembly& out) {
  Eigen::VectorXd f;
  Eigen::MatrixXd dfdx;
  std::vector<Vec3> x;
  for (size_t k = 0; k < faces_.size(); ++k) {
    const PressureSpec& ps = spec_.pressure[faces_[k].load];
    const double p = ps.value * ramp_factor(ps.ramp, state.time, spec_.t_end);
    x.clear();
    for (int a : faces_[k].nodes) x.push_back(spec_.mesh.nodes[a] + state.x.segment<3>(u_->node_dof(a)));
    follower_pressure(x, p, f, dfdx);
    out.add_tangent(local_[k], -dfdx);  // R = f_int − f_ext: K gets −∂f_ext/∂ū
    out.add_external(dofs_[k], f);
  }
}

}  // namespace fe2
