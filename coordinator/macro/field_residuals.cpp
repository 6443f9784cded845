#include "coordinator/macro/field_residuals.h"

#include <algorithm>
#include <cmath>

namespace fe2 {

std::vector<double> field_residual_norms(const MacroSystem& system, const Eigen::VectorXd& f_int,
                                         const Eigen::VectorXd& f_ext, const std::vector<Eigen::VectorXd>& scales) {
  const MacroConstraints& c = system.constraints();
  Eigen::VectorXd R = Eigen::VectorXd::Zero(system.num_dofs());
  for (int dof = 0; dof < system.num_dofs(); ++dof)
    if (c.is_master(dof)) R[dof] = f_int[dof] - f_ext[dof];
  for (const auto& tie : c.ties())
    if (tie.shares_equation) R[tie.master] += f_int[tie.dof] - f_ext[tie.dof];
  std::vector<double> norms;
  for (const Field& field : system.fields()) {
    const Eigen::Index o = field.offset(), n = field.size();
    double value = 0.0;
    switch (field.decl().norm) {
      case ResidualNorm::relative_to_load: {
        // Σ R_d² by fused multiply-adds, in DOF order: the same sum on every compiler.
        double r2 = 0.0;
        for (Eigen::Index d = o; d < o + n; ++d) r2 = std::fma(R[d], R[d], r2);
        const double floor = scales[field.id()].size() > 0 ? scales[field.id()].norm() : 0.0;
        const double F_ref = std::max({f_int.segment(o, n).norm(), f_ext.segment(o, n).norm(), floor});
        value = F_ref > 0 ? std::sqrt(r2) / F_ref : std::sqrt(r2);
        break;
      }
      case ResidualNorm::scaled_l2:
        // cwiseAbs2().sum(), as norm() does, over an expression without direct access:
        // the reduction then groups its terms alike whatever the block's alignment.
        value = std::sqrt(R.segment(o, n).cwiseAbs2().sum()) / scales[field.id()].norm();
        break;
      case ResidualNorm::scaled_max:
        for (Eigen::Index k = 0; k < n; ++k) value = std::max(value, std::abs(R[o + k]) / scales[field.id()][k]);
        break;
    }
    norms.push_back(value);
  }
  return norms;
}

}  // namespace fe2
