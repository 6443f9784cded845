#include "coordinator/tet_kinematics.h"

namespace fe2 {

std::vector<TetPoint> tet_points(const TetMesh& mesh) {
  std::vector<TetPoint> pts(mesh.num_tets());
  for (int e = 0; e < mesh.num_tets(); ++e) {
    const auto& t = mesh.tets[e];
    Mat3 D;  // columns X_a − X_0, a = 1..3
    for (int a = 1; a < 4; ++a) D.col(a - 1) = mesh.nodes[t[a]] - mesh.nodes[t[0]];
    const Mat3 Dinv = D.inverse();
    TetPoint& p = pts[e];
    // N_a for a = 1..3 are the rows of D⁻¹ applied to (X − X_0); N_0 = 1 − Σ N_a.
    for (int a = 1; a < 4; ++a) p.grad.col(a) = Dinv.row(a - 1).transpose();
    p.grad.col(0) = -(p.grad.col(1) + p.grad.col(2) + p.grad.col(3));
    p.volume = D.determinant() / 6.0;
    p.centroid.setZero();
    for (int a = 0; a < 4; ++a) p.centroid += 0.25 * mesh.nodes[t[a]];
    p.B.setZero();
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i)
        for (int J = 0; J < 3; ++J) p.B(i + 3 * J, 3 * a + i) = p.grad(J, a);
  }
  return pts;
}

}  // namespace fe2
