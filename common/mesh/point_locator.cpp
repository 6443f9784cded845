#include "common/mesh/point_locator.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fe2 {

namespace {

struct TetPosition {
  std::array<double, 4> bary{};
  double min_bary = -std::numeric_limits<double>::infinity();
  /// Largest distance of X beyond one of the tet's face planes (<= 0 inside). It equals
  /// the distance to the tet when the nearest point is inside a face, and underestimates
  /// it near edges and corners, which is harmless at snapping tolerances.
  double outside = std::numeric_limits<double>::infinity();
};

TetPosition position_in_tet(const TetMesh& m, int e, const Vec3& X) {
  const auto& t = m.tets[e];
  const Vec3& x0 = m.nodes[t[0]];
  Mat3 J;
  for (int a = 0; a < 3; ++a) J.col(a) = m.nodes[t[a + 1]] - x0;
  TetPosition p;
  if (!(std::abs(J.determinant()) > 0.0)) return p;  // degenerate tet: never chosen
  const Mat3 Jinv = J.inverse();
  const Vec3 l = Jinv * (X - x0);
  p.bary = {1.0 - l.sum(), l[0], l[1], l[2]};
  // Rows of Jinv are the gradients of barycentric coordinates 1..3; λ_i/|∇λ_i| is the
  // signed distance of X from face i (positive on the tet's side).
  std::array<Vec3, 4> grad = {-(Jinv.row(0) + Jinv.row(1) + Jinv.row(2)).transpose(), Jinv.row(0).transpose(),
                              Jinv.row(1).transpose(), Jinv.row(2).transpose()};
  p.outside = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i) p.outside = std::max(p.outside, -p.bary[i] / grad[i].norm());
  p.min_bary = *std::min_element(p.bary.begin(), p.bary.end());
  return p;
}

double bounding_box_diagonal(const TetMesh& m) {
  Vec3 lo = m.nodes.front(), hi = m.nodes.front();
  for (const Vec3& x : m.nodes) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  return (hi - lo).norm();
}

}  // namespace

MeshPoint locate_point(const TetMesh& m, const Vec3& X, double tol) {
  FE2_CHECK(m.num_tets() > 0, "locate_point on an empty mesh");
  int deepest = -1, nearest = -1;
  TetPosition best_inside, best_outside;
  for (int e = 0; e < m.num_tets(); ++e) {
    const TetPosition p = position_in_tet(m, e, X);
    if (p.min_bary > best_inside.min_bary) {
      best_inside = p;
      deepest = e;
    }
    if (p.outside < best_outside.outside) {
      best_outside = p;
      nearest = e;
    }
  }
  if (deepest >= 0 && best_inside.min_bary >= 0.0) return {deepest, best_inside.bary};

  const double limit = tol * bounding_box_diagonal(m);
  if (nearest < 0 || !(best_outside.outside <= limit))
    throw InputError(fmt::format("point ({}, {}, {}) lies outside the mesh (by about {:.3g}), expected a "
                                 "point inside or within {:.3g} of the mesh",
                                 X.x(), X.y(), X.z(), best_outside.outside, limit));
  MeshPoint snapped{nearest, best_outside.bary};
  double sum = 0.0;
  for (double& b : snapped.bary) sum += (b = std::max(b, 0.0));
  for (double& b : snapped.bary) b /= sum;
  return snapped;
}

}  // namespace fe2
