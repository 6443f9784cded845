#pragma once
// Follower pressure on a linear triangle of the deformed surface. With the traction
// t = −p n on the current configuration, the consistent nodal force is the same on
// each of the three nodes:
//   f_a = −(p/6) (x₁ − x₀) × (x₂ − x₀),   a = 0, 1, 2,
// and its derivative with respect to the nodal positions (unsymmetric in general):
//   ∂f_a/∂x₀ = −(p/6)([b]× − [a]×),  ∂f_a/∂x₁ = (p/6)[b]×,  ∂f_a/∂x₂ = −(p/6)[a]×
// with a = x₁ − x₀, b = x₂ − x₀ and [v]× the cross-product matrix (v × w = [v]× w).
#include "common/tensor9.h"

namespace fe2 {

/// x: current positions of the triangle's nodes. f: 9 (node-major 3a + i), dfdx: 9x9.
void follower_pressure(const std::array<Vec3, 3>& x, double p, Eigen::Matrix<double, 9, 1>& f,
                       Eigen::Matrix<double, 9, 9>& dfdx);

}  // namespace fe2
