#pragma once
// Follower pressure on one deformed surface triangle, linear (3 nodes) or quadratic
// (6 nodes, TetMesh::face_nodes order). With the traction t = −p n on the current
// configuration and the surface map x(ξ) = Σ x_a N_a(ξ), n da = (a₁ × a₂) dξ with
// a_α = ∂x/∂ξ_α, the consistent nodal force and its derivative are
//   f_a = −p ∫ N_a (a₁ × a₂) dξ
//   ∂f_a/∂x_b = −p ∫ N_a (∂N_b/∂ξ₂ [a₁]× − ∂N_b/∂ξ₁ [a₂]×) dξ      (unsymmetric)
// with [v]× the cross-product matrix (v × w = [v]× w). The integrand has degree
// 3·order − 2 (N_a times a₁ × a₂), integrated exactly. For a linear triangle
// f_a = −(p/6) (x₁ − x₀) × (x₂ − x₀) on every node.
#include "common/tensor9.h"

#include <vector>

namespace fe2 {

/// x: current positions of the triangle's 3 or 6 nodes. f: 3n (node-major 3a + i),
/// dfdx: 3n x 3n.
void follower_pressure(const std::vector<Vec3>& x, double p, Eigen::VectorXd& f, Eigen::MatrixXd& dfdx);

}  // namespace fe2
