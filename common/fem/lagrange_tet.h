#pragma once
// Lagrange shape functions on tetrahedra and triangles in barycentric coordinates λ,
// node order of TetMesh::element_nodes / face_nodes (VTK):
//   P1: N_a = λ_a.
//   P2: vertices N_a = λ_a(2λ_a − 1); edge (a, b): N = 4 λ_a λ_b.
// Reference gradients are with respect to ξ = (λ1, λ2, λ3) (λ0 = 1 − ξ1 − ξ2 − ξ3), so
// the isoparametric map x(ξ) = Σ x_a N_a(ξ) has Jacobian J = Σ x_a ⊗ ∂N_a/∂ξ and the
// physical gradients are ∇_X N_a = J⁻ᵀ ∂N_a/∂ξ.
#include "common/fem/quadrature.h"

namespace fe2 {

/// Values (n) and ξ-gradients (3 x n) of the order-1 (n = 4) or order-2 (n = 10) tet basis.
void tet_shape(int order, const Vec4& bary, Eigen::VectorXd& N, Eigen::Matrix<double, 3, Eigen::Dynamic>& dN);

/// Values (n) and gradients with respect to (λ1, λ2) (2 x n) of the order-1 (n = 3) or
/// order-2 (n = 6) triangle basis.
void triangle_shape(int order, const Vec3& bary, Eigen::VectorXd& N,
                    Eigen::Matrix<double, 2, Eigen::Dynamic>& dN);

/// Number of nodes of the tet (4 or 10) and triangle (3 or 6) of an order.
inline int tet_nodes(int order) { return order == 1 ? 4 : 10; }
inline int triangle_nodes(int order) { return order == 1 ? 3 : 6; }

}  // namespace fe2
