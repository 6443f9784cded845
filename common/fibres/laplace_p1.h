#pragma once
// The Laplace–Dirichlet problems of rule-based fibres: ∇²u = 0 in the wall, u given on
// named node sets, zero flux elsewhere; linear (P1) elements on the tet vertices (a
// quadratic mesh's edge nodes are not unknowns: the directions need no more).
#include "common/mesh/TetMesh.h"

#include <array>
#include <string>
#include <vector>

namespace fe2 {

/// u = value on the nodes of a named set.
struct LaplaceDirichlet {
  std::string set;          ///< its name (for messages)
  std::vector<int> nodes;   ///< mesh node indices (non-vertex nodes are ignored)
  double value = 0.0;
};

/// Solves with Eigen's SimplicialLDLT on the free vertices; returns u per mesh node
/// (0 at nodes that are not tet vertices). `what` names the problem in messages.
/// Throws InputError if a node gets two different values (naming both sets) or if a
/// part of the mesh touches no Dirichlet node (the system is singular).
std::vector<double> solve_laplace_p1(const TetMesh& mesh, const std::vector<LaplaceDirichlet>& bcs,
                                     const std::string& what);

/// Gradients of the four P1 shape functions (barycentric coordinates) of tet e.
std::array<Vec3, 4> p1_gradients(const TetMesh& mesh, int e);

}  // namespace fe2
