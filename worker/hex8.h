#pragma once
// Trilinear 8-node hexahedron with 2x2x2 Gauss quadrature.
// Reference node order (VTK/Gmsh): ξ signs (-,-,-) (+,-,-) (+,+,-) (-,+,-) then the
// same with ζ = +.
#include "common/mesh/HexMesh.h"

#include <Eigen/Dense>

#include <array>

namespace fe2 {

/// Physical shape-function gradients at the 8 Gauss points of one hex:
/// grad[q] is 3x8, column a = ∇_X N_a at point q; weight[q] = w_q det J_q.
struct HexGeometry {
  std::array<Eigen::Matrix<double, 3, 8>, 8> grad;
  std::array<double, 8> weight;
};

/// Computes the geometry of hex `e`; throws fe2::InputError if det J <= 0 at a Gauss
/// point (an inverted or badly ordered element), naming the element.
HexGeometry hex_geometry(const HexMesh& mesh, int e);

}  // namespace fe2
