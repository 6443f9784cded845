#include "worker/hex8.h"

#include "common/error.h"

#include <cmath>

namespace fe2 {

namespace {
constexpr int kSign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                             {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
}

HexGeometry hex_geometry(const HexMesh& mesh, int e) {
  HexGeometry g;
  const double gp = 1.0 / std::sqrt(3.0);
  // Relative to the first node: J = Σ X_a ⊗ ∇_ξN_a does not depend on where the element
  // is (Σ ∇_ξN_a = 0), and without the cancellation of absolute coordinates its rounding
  // does not either, so equal shapes give equal bits (MicroModel keeps one geometry per
  // distinct shape) whatever the compiler contracts into FMAs.
  Eigen::Matrix<double, 8, 3> X;
  const Vec3 origin = mesh.nodes[mesh.hexes[e][0]];
  for (int a = 0; a < 8; ++a) X.row(a) = (mesh.nodes[mesh.hexes[e][a]] - origin).transpose();
  for (int q = 0; q < 8; ++q) {
    const double xi[3] = {kSign[q][0] * gp, kSign[q][1] * gp, kSign[q][2] * gp};
    // dN/dξ (8x3) of N_a = ⅛ Π_d (1 + s_ad ξ_d)
    Eigen::Matrix<double, 8, 3> dN;
    for (int a = 0; a < 8; ++a)
      for (int d = 0; d < 3; ++d) {
        double v = 0.125 * kSign[a][d];
        for (int o = 0; o < 3; ++o)
          if (o != d) v *= 1.0 + kSign[a][o] * xi[o];
        dN(a, d) = v;
      }
    const Mat3 J = X.transpose() * dN;  // J_ij = ∂X_i/∂ξ_j
    const double detJ = J.determinant();
    if (!(detJ > 0.0))
      throw InputError(fmt::format(
          "micro mesh: hexahedron {} is inverted or badly ordered (det J = {:.3e} at Gauss "
          "point {}); expected the VTK/Gmsh node order with positive volume",
          e, detJ, q));
    g.grad[q] = (dN * J.inverse()).transpose();  // ∇_X N = J⁻ᵀ ∇_ξ N
    g.weight[q] = detJ;                          // Gauss weights are 1 for 2-point rule
  }
  return g;
}

}  // namespace fe2
