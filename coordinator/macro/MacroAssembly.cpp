#include "coordinator/macro/MacroTerm.h"

namespace fe2 {

MacroAssembly::MacroAssembly(const MacroSystem& system, std::vector<double>& values)
    : system_(system), values_(values) {
  clear();
}

void MacroAssembly::clear() {
  std::fill(values_.begin(), values_.end(), 0.0);
  internal_ = Eigen::VectorXd::Zero(system_.num_dofs());
  external_ = Eigen::VectorXd::Zero(system_.num_dofs());
  rhs_.assign(system_.num_free(), 0.0);
}

void MacroAssembly::add_tangent(int local, const Eigen::MatrixXd& K) {
  system_.add(local, K, values_);
  if (!lift_) return;
  const auto& rows = system_.local_rows(local);
  const auto& cols = system_.local_cols(local);
  for (size_t c = 0; c < cols.size(); ++c) {
    const double du = (*lift_)[cols[c]];
    if (du == 0.0) continue;
    for (size_t r = 0; r < rows.size(); ++r)
      if (system_.eq(rows[r]) >= 0) rhs_[system_.eq(rows[r])] -= K(r, c) * du;
  }
}

void MacroAssembly::add_internal(const std::vector<int>& dofs, const Eigen::VectorXd& f_true,
                                 const Eigen::VectorXd& f_newton) {
  for (size_t k = 0; k < dofs.size(); ++k) {
    internal_[dofs[k]] += f_true[k];
    if (system_.eq(dofs[k]) >= 0) rhs_[system_.eq(dofs[k])] -= f_newton[k];
  }
}

void MacroAssembly::add_external(const std::vector<int>& dofs, const Eigen::VectorXd& f) {
  for (size_t k = 0; k < dofs.size(); ++k) {
    external_[dofs[k]] += f[k];
    if (system_.eq(dofs[k]) >= 0) rhs_[system_.eq(dofs[k])] += f[k];
  }
}

}  // namespace fe2
