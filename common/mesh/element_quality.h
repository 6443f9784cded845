#pragma once
// Quality of a (curved) tetrahedron: how far its isoparametric map is from affine.
//
// For a P2 tet x(ξ) = Σ x_a N_a(ξ) the Jacobian determinant det J(ξ) is a cubic in ξ;
// a straight-sided tet has it constant. The quality reported here is the Jacobian ratio
//
//   q = min_ξ det J(ξ) / max_ξ det J(ξ)   (1: affine; ≤ 0: the map folds over itself)
//
// sampled on the order-4 barycentric lattice (35 points: vertices, edge and face points,
// interior) together with the element's quadrature points. Sampling can miss a minimum
// between lattice points, so q is an upper bound of the true ratio; it is the measure
// Gmsh reports as "minSJ/maxSJ"-like distortion and what a user can act on (remesh).
// Also the element's shape (aspect) by the volume/edge ratio η = 6√2 V / l_rms³ of its
// vertices (1 for the regular tet).
#include "common/mesh/TetMesh.h"

#include <string>

namespace fe2 {

struct ElementQuality {
  int element = -1;
  Vec3 centroid = Vec3::Zero();   ///< mean of the four vertices
  double min_det_J = 0.0;         ///< over the samples (reference tet of volume 1/6)
  double max_det_J = 0.0;
  double jacobian_ratio = 1.0;    ///< min_det_J / max_det_J
  double shape = 1.0;             ///< η of the vertex tet
};

/// η = 6√2 V / l_rms³ of a tet of vertices x0..x3 (1 regular, → 0 flat, < 0 inverted).
double tet_shape_quality(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3);

/// The quality of element e (linear meshes: ratio 1, only the shape varies).
ElementQuality element_quality(const TetMesh& m, int e);

/// "element 123 (centroid (0.1, 2.3, -13.0), Jacobian ratio 0.12, shape 0.31)".
std::string describe(const ElementQuality& q);

/// The element of lowest Jacobian ratio (ties: lowest shape), for a start-up note.
ElementQuality worst_element(const TetMesh& m);

}  // namespace fe2
