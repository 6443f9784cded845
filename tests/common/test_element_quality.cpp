// Element quality of curved tets (common/mesh/element_quality.h) against the closed form
// of a P2 tet with one edge node moved along its edge.
#include "common/mesh/element_quality.h"

#include <gtest/gtest.h>

namespace fe2 {
namespace {

/// The unit reference tet, quadratic, with the node of edge 01 at (1/2 + δ, 0, 0).
TetMesh reference_tet(double delta) {
  TetMesh m;
  m.nodes = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  m.tets = {{0, 1, 2, 3}};
  m.region = {1};
  make_quadratic(m);
  m.nodes[m.edge_node(0, 1)] += Vec3(delta, 0, 0);
  return m;
}

TEST(ElementQuality, StraightTetIsAffine) {
  const ElementQuality q = element_quality(reference_tet(0.0), 0);
  EXPECT_NEAR(q.jacobian_ratio, 1.0, 1e-14);
  EXPECT_NEAR(q.min_det_J, 1.0, 1e-14);
  // η of the corner tet (edges 1, 1, 1, √2, √2, √2): 6√2 (1/6) / (√1.5)³.
  EXPECT_NEAR(q.shape, std::sqrt(2.0) / std::pow(1.5, 1.5), 1e-14);
  EXPECT_NEAR(q.centroid[0], 0.25, 1e-15);
}

// x = ξ + 4δ λ0 λ1 e_x: det J = 1 + 4δ (λ0 − λ1), extreme at vertices 0 and 1 (lattice
// points): ratio (1 − 4δ)/(1 + 4δ).
TEST(ElementQuality, CurvedEdgeGivesTheClosedFormRatio) {
  for (double delta : {0.05, 0.1, 0.2}) {
    const ElementQuality q = element_quality(reference_tet(delta), 0);
    EXPECT_NEAR(q.min_det_J, 1.0 - 4 * delta, 1e-13) << delta;
    EXPECT_NEAR(q.max_det_J, 1.0 + 4 * delta, 1e-13) << delta;
    EXPECT_NEAR(q.jacobian_ratio, (1.0 - 4 * delta) / (1.0 + 4 * delta), 1e-13) << delta;
  }
}

TEST(ElementQuality, FoldedElementHasNegativeRatio) {
  const ElementQuality q = element_quality(reference_tet(0.3), 0);  // det J = −0.2 at vertex 0
  EXPECT_LT(q.jacobian_ratio, 0.0);
  EXPECT_NE(describe(q).find("element 0 (centroid (0.25, 0.25, 0.25)"), std::string::npos) << describe(q);
}

TEST(ElementQuality, WorstElementIsTheCurvedOne) {
  TetMesh m;
  m.nodes = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 1)};
  m.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
  m.region = {1, 1};
  make_quadratic(m);
  m.nodes[m.edge_node(0, 1)] += Vec3(0.1, 0, 0);
  EXPECT_EQ(worst_element(m).element, 0);
  EXPECT_NEAR(worst_element(m).jacobian_ratio, 0.6 / 1.4, 1e-13);
}

}  // namespace
}  // namespace fe2
