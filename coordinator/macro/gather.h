#pragma once
// The entries of a global vector at a local matrix's DOFs.
#include <Eigen/Dense>

#include <vector>

namespace fe2 {

inline Eigen::VectorXd gather(const Eigen::VectorXd& x, const std::vector<int>& dofs) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(dofs.size()));
  for (size_t k = 0; k < dofs.size(); ++k) v[static_cast<Eigen::Index>(k)] = x[dofs[k]];
  return v;
}

}  // namespace fe2
