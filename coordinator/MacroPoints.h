#pragma once
// The macro integration points: one point model (FE² unit or macro law) per point.
// Only the wall's elements have points (RunSpec::wall_elements; another region's element
// has none). Point ids are independent of element ids: points are numbered element after
// element, the points of element e being first_point(e) .. first_point(e + 1) − 1 (a quadrature
// rule per element type: degree 2(order − 1), one point for linear tets, four for
// quadratic ones, unless the spec asks for another degree).
//
// At point k of element e (isoparametric, TetMesh::element_nodes order):
//   ∇N_a = J⁻ᵀ ∂N_a/∂ξ,  J = Σ_a X_a ⊗ ∂N_a/∂ξ,   |ē_k| = w_k det J
//   B̄_k (9 x 3n) maps nodal displacements (node-major 3a + i) to the column-major
//   9-vector Z̄: Z̄_iJ = Σ_a ū_ai ∂N_a/∂X̄_J, so B̄(i + 3J, 3a + i) = ∂N_a/∂X̄_J.
#include "common/fem/quadrature.h"
#include "common/mesh/TetMesh.h"

#include <vector>

namespace fe2 {

struct MacroPoint {
  int element = -1;
  Eigen::Matrix<double, 9, Eigen::Dynamic> B;  ///< B̄_k
  Eigen::VectorXd N;                           ///< displacement shape functions at the point
  Vec4 bary = Vec4::Zero();                    ///< λ of the element's vertices (P1 pressure)
  double volume = 0.0;                         ///< |ē_k| = w_k det J
  Vec3 X = Vec3::Zero();                       ///< reference position X̄_k
};

class MacroPoints {
 public:
  /// Points of the `elements` of `mesh` (ascending; empty: every element) with a tet
  /// rule of `degree` (−1: 2(order − 1)). Throws InputError naming the element if its
  /// Jacobian is not positive at a point.
  MacroPoints(const TetMesh& mesh, int degree = -1, const std::vector<int>& elements = {});

  int size() const { return static_cast<int>(points_.size()); }
  const MacroPoint& operator[](int k) const { return points_[k]; }
  int first_point(int e) const { return first_[e]; }
  int points_per_element() const { return per_element_; }
  int degree() const { return degree_; }
  /// The points of the given elements, ascending.
  std::vector<int> points_of(const std::vector<int>& elements) const;

 private:
  std::vector<MacroPoint> points_;
  std::vector<int> first_;
  int per_element_ = 1;
  int degree_ = 0;
};

}  // namespace fe2
