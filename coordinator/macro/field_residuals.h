#pragma once
// The convergence test's measure of each field (FieldDecl::norm): the residual
// R = f_int − f_ext condensed onto the free equations (a tied DOF's residual adds to its
// master's; prescribed DOFs carry reactions and following DOFs dropped equations, not
// residuals), then per field
//   relative_to_load  ‖R‖ / max(‖f_int‖, ‖f_ext‖, ‖s‖)   (forces; s a floor its terms may
//                     report, for fields whose forces can all vanish, e.g. a uniform flow;
//                     ‖R‖ if all vanish)
//   scaled_l2         ‖R‖ / ‖s‖
//   scaled_max        max_i |R_i| / s_i
// with s the scale the field's terms report (MacroTerm::add_residual_scale).
#include "coordinator/macro/MacroSystem.h"

#include <Eigen/Dense>

#include <vector>

namespace fe2 {

/// Per field (table order). `f_int`, `f_ext` over every DOF and `scales` per field (its
/// size), each already summed over the coordinators.
std::vector<double> field_residual_norms(const MacroSystem& system, const Eigen::VectorXd& f_int,
                                         const Eigen::VectorXd& f_ext, const std::vector<Eigen::VectorXd>& scales);

}  // namespace fe2
