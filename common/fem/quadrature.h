#pragma once
// Quadrature on the reference tetrahedron {λ ≥ 0, Σλ = 1} and triangle, points given by
// barycentric coordinates and weights summing to the reference measure (1/6 and 1/2).
//   tet degree 1: the centroid;  tet degree 2: the 4-point rule with
//   a = (5 + 3√5)/20, b = (5 − √5)/20 (Stroud T3:2-1);
//   any other degree: a collapsed (Duffy) Gauss–Legendre product rule, exact for
//   polynomials of that degree (n points per direction with 2n − 1 ≥ degree + 2 on the
//   tet, degree + 1 on the triangle, absorbing the collapse's Jacobian).
// Weights are positive in every rule (a point model per point needs a positive volume).
#include "common/tensor9.h"

#include <vector>

namespace fe2 {

using Vec4 = Eigen::Vector4d;

struct TetQuadraturePoint {
  Vec4 bary;       ///< λ0..λ3
  double weight;   ///< on the reference tet (Σ = 1/6)
};

struct TriangleQuadraturePoint {
  Vec3 bary;       ///< λ0..λ2
  double weight;   ///< on the reference triangle (Σ = 1/2)
};

/// A rule exact for polynomials of total degree `degree` (≥ 0).
std::vector<TetQuadraturePoint> tet_rule(int degree);
std::vector<TriangleQuadraturePoint> triangle_rule(int degree);

/// The macro points' default degree for a mesh order: 2(order − 1) (exact stiffness on
/// affine elements); coordinator/MacroPoints and per-point fibre files number points by it.
inline int default_point_degree(int order) { return 2 * (order - 1); }

}  // namespace fe2
