// MicroModel keeps one geometry per distinct element shape (worker/MicroModel.h):
// every element must still see exactly its own ∇N and weights.
#include "tests/worker/unit_fixtures.h"
#include "worker/hex8.h"

#include <gtest/gtest.h>

#include <cstring>

namespace fe2 {
namespace {

bool same_bits(const HexGeometry& a, const HexGeometry& b) {
  return std::memcmp(&a, &b, sizeof(HexGeometry)) == 0;
}

TEST(ElementGeometry, EveryElementSeesItsOwnGeometry) {
  const MicroModelPtr model = test::two_cell_model({}, {6, 5, 4});
  const int ne = model->num_elements();
  // A voxel cell has few shapes (equal up to the rounding of the node coordinates).
  EXPECT_LT(model->num_distinct_geometries(), ne / 2);
  EXPECT_GT(model->num_distinct_geometries(), 0);
  for (int e = 0; e < ne; ++e)
    ASSERT_TRUE(same_bits(model->geometry(e), hex_geometry(model->mesh(), e))) << "element " << e;
}

TEST(ElementGeometry, DistortedElementsKeepTheirOwn) {
  // Interior nodes moved apart: no two elements share a shape, and each keeps its own.
  CellLayout c;
  c.kind = "homogeneous";
  c.size = Vec3(1.0, 1.0, 1.0);
  c.resolution = {4, 4, 4};
  HexMesh mesh = make_cell_mesh(c);
  for (Vec3& x : mesh.nodes) {
    const bool interior = (x.array() > 1e-12).all() && (x.array() < 1.0 - 1e-12).all();
    if (interior) x += 0.02 * Vec3(std::sin(7 * x[1]), std::cos(5 * x[2]), std::sin(3 * x[0]));
  }
  const auto model = std::make_shared<const MicroModel>(
      mesh, std::vector<MaterialPtr>{std::make_shared<NeoHookean>(1.0e3, 0.3)},
      MicroSolverOptions{}, "distorted");
  EXPECT_EQ(model->num_distinct_geometries(), model->num_elements());
  for (int e = 0; e < model->num_elements(); ++e)
    ASSERT_TRUE(same_bits(model->geometry(e), hex_geometry(model->mesh(), e))) << "element " << e;
}

}  // namespace
}  // namespace fe2
