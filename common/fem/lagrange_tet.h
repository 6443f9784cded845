#pragma once
// Lagrange shape functions on tetrahedra and triangles in barycentric coordinates λ,
// node order of TetMesh::element_nodes / face_nodes (VTK):
//   P1: N_a = λ_a.
//   P2: vertices N_a = λ_a(2λ_a − 1); edge (a, b): N = 4 λ_a λ_b.
// Reference gradients are with respect to ξ = (λ1, λ2, λ3) (λ0 = 1 − ξ1 − ξ2 − ξ3), so
// the isoparametric map x(ξ) = Σ x_a N_a(ξ) has Jacobian J = Σ x_a ⊗ ∂N_a/∂ξ and the
// physical gradients are ∇_X N_a = J⁻ᵀ ∂N_a/∂ξ.
#include "common/fem/quadrature.h"

#include <vector>

namespace fe2 {

/// Values (n) and ξ-gradients (3 x n) of the order-1 (n = 4) or order-2 (n = 10) tet basis.
void tet_shape(int order, const Vec4& bary, Eigen::VectorXd& N, Eigen::Matrix<double, 3, Eigen::Dynamic>& dN);

/// Second ξ-derivatives ∂²N_a/∂ξ∂ξ (n symmetric 3 x 3, constant on the element): zero
/// for order 1; P2 vertex 4 ∇λ_a⊗∇λ_a, edge (a, b) 4(∇λ_a⊗∇λ_b + ∇λ_b⊗∇λ_a).
std::vector<Mat3> tet_shape_hessians(int order);

/// ΔN_a = tr ∂²N_a/∂x∂x at a point of the isoparametric element with nodes x (3 x n),
/// J⁻¹ = ∂ξ/∂x and ∇N (3 x n) there. With J = ∂x/∂ξ,
///   ∂²N/∂ξ∂ξ = Jᵀ (∂²N/∂x∂x) J + Σ_k ∂N/∂x_k ∂²x_k/∂ξ∂ξ,
/// so ∂²N/∂x∂x = J⁻ᵀ (∂²N/∂ξ∂ξ − Σ_k ∂N/∂x_k ∂²x_k/∂ξ∂ξ) J⁻¹: exact on curved P2
/// elements (the second term vanishes on straight-sided ones), zero for order 1.
Eigen::VectorXd tet_shape_laplacians(int order, const Eigen::Matrix3Xd& x, const Mat3& Jinv,
                                     const Eigen::Matrix3Xd& gN);

/// The physical Hessians ∂²N_a/∂x∂x themselves (n symmetric 3 x 3; as above), whose
/// traces are tet_shape_laplacians: what the laplacians' shape derivatives need.
std::vector<Mat3> tet_shape_physical_hessians(int order, const Eigen::Matrix3Xd& x, const Mat3& Jinv,
                                              const Eigen::Matrix3Xd& gN);

/// Values (n) and gradients with respect to (λ1, λ2) (2 x n) of the order-1 (n = 3) or
/// order-2 (n = 6) triangle basis.
void triangle_shape(int order, const Vec3& bary, Eigen::VectorXd& N,
                    Eigen::Matrix<double, 2, Eigen::Dynamic>& dN);

/// Number of nodes of the tet (4 or 10) and triangle (3 or 6) of an order.
inline int tet_nodes(int order) { return order == 1 ? 4 : 10; }
inline int triangle_nodes(int order) { return order == 1 ? 3 : 6; }

}  // namespace fe2
