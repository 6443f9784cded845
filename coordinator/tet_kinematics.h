#pragma once
// Macro kinematics of a 4-node tetrahedron with one integration point at the centroid
// (the seed element; code is per integration point so higher orders fit later).
// B̄ (9x12) maps the element's nodal displacements (node-major, 3a + i) to the
// column-major 9-vector Z̄: Z̄_iJ = Σ_a ū_ai ∂N_a/∂X̄_J, so B̄(i + 3J, 3a + i) = ∂N_a/∂X̄_J.
#include "common/mesh/TetMesh.h"

#include <vector>

namespace fe2 {

struct TetPoint {
  Eigen::Matrix<double, 9, 12> B;  ///< B̄_k
  Eigen::Matrix<double, 3, 4> grad; ///< ∇N_a (columns)
  double volume = 0.0;              ///< |ē_k|
  Vec3 centroid = Vec3::Zero();     ///< X̄_k
};

/// One integration point per tet (the centroid).
std::vector<TetPoint> tet_points(const TetMesh& mesh);

}  // namespace fe2
