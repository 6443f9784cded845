#pragma once
// Finding the tetrahedron (and barycentric coordinates) that holds a reference point,
// e.g. for probes and point loads given by coordinates in a spec.
#include "common/mesh/TetMesh.h"

#include <array>

namespace fe2 {

struct MeshPoint {
  int tet = -1;                  ///< element index
  std::array<double, 4> bary{};  ///< barycentric coordinates w.r.t. the tet's nodes, sum 1, all >= 0
};

/// Locates X in the mesh by brute force over all tets (O(num_tets); fine for probes).
/// Inside the mesh it returns the tet in which X lies deepest (largest smallest
/// barycentric coordinate), so points on shared faces pick a well-conditioned tet.
/// A point outside by at most tol * (bounding-box diagonal) is snapped to the nearest
/// tet: its barycentric coordinates are clamped to >= 0 and renormalized. Farther out,
/// throws InputError naming the coordinates.
MeshPoint locate_point(const TetMesh& m, const Vec3& X, double tol = 1e-9);

}  // namespace fe2
