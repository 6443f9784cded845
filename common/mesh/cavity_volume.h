#pragma once
// The volume of a ventricular cavity in the deformed configuration, and its derivative.
//
// The cavity is bounded by a named endocardial surface (3- or 6-node triangles, oriented
// out of the solid, i.e. into the cavity) and, where that surface is open, by a fan of
// triangles from the centroid c of its boundary-ring nodes to each boundary edge (the
// base need not stay planar once deformed). By the divergence theorem
//   V = -(1/3) ∮ x · n da,   x = X + u,
// over that closed surface with normals into the cavity; ∮ x·n da of each triangle is
// integrated exactly (x·(x_ξ × x_η) is a polynomial of degree 4 on a 6-node triangle).
// On a quadratic mesh a cap triangle's boundary edge uses the mesh's (curved) edge node
// and its two edges to c are straight, so the closed surface is watertight and V does
// not change under a rigid translation.
#include "common/mesh/TetMesh.h"

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

namespace fe2 {

struct CavityVolume {
  double volume = 0.0;  ///< V, positive for a cavity the surface wraps around
  /// ∂V/∂u as (dof, value), dof = 3·node + component, ascending, each dof once;
  /// includes the dependence through the ring centroid c.
  std::vector<std::pair<int, double>> dV_du;
};

/// V and ∂V/∂u for the cavity of the named face at nodal displacements u (node-major,
/// u[3a + i], size 3·num_nodes). A closed surface gets no cap; several boundary loops
/// all fan to the one centroid. Throws InputError if the mesh has no face `face`
/// (naming the faces it has) or if u has the wrong size.
CavityVolume cavity_volume(const TetMesh& m, const std::string& face, const Eigen::VectorXd& u);

}  // namespace fe2
