// A macro domain with regions: only the wall's regions (mesh.wall_regions) carry the
// displacement, the pressure and the point models; another region (a cavity to be) is
// there for fields that live on it and costs the wall nothing. One element partition
// serves every term (MacroPartition), balanced by the cost of each element kind.
#include "common/mesh/box_mesh.h"
#include "coordinator/LocalPoints.h"
#include "coordinator/farm/FarmLayout.h"
#include "coordinator/macro/macro_scene.h"
#include "tests/coordinator/scene_fixtures.h"

#include <gtest/gtest.h>

#include <map>
#include <set>

namespace fe2 {
namespace {

/// The box [lo_x, 1] x [0, 1]² pulled on ymax and held on xmax. With `two_slabs` the box
/// is [0, 1]³ cut at x = 1/2 into region 1 (x < 1/2) and the wall, region 2.
json pulled_box(bool two_slabs, int order) {
  json mesh = {{"kind", "box"}, {"hi", {1, 1, 1}}, {"order", order}};
  if (two_slabs) {
    mesh["divisions"] = {4, 2, 2};
    mesh["region_slabs"] = {{"axis", "x"}, {"count", 2}};
    mesh["wall_regions"] = json::array({2});
  } else {
    mesh["lo"] = {0.5, 0, 0};
    mesh["divisions"] = {2, 2, 2};
  }
  return {{"mesh", mesh},
          {"models", {{"m", {{"kind", "macro_law"}, {"material", test::nh(1e3, 0.3)}}}}},
          {"dirichlet", {{{"set", "xmax"}}, {{"set", "ymax"}, {"value", {0.0, 0.02, 0.005}}}}},
          {"time", {{"t_end", 1.0}, {"steps", 2}}},
          {"newton", {{"rtol", 1e-11}, {"max_iterations", 20}}},
          {"output", {{"vtu", false}}}};
}

struct Key {
  long x, y, z;
  bool operator<(const Key& o) const { return std::tie(x, y, z) < std::tie(o.x, o.y, o.z); }
};
Key key(const Vec3& X) { return {std::lround(X.x() * 1e6), std::lround(X.y() * 1e6), std::lround(X.z() * 1e6)}; }

TEST(WallRegions, OnlyTheWallCarriesPointsAndDisplacementAndTheOtherRegionChangesNothing) {
  for (int order : {1, 2}) {
    const RunSpec spec = read_run_spec(pulled_box(true, order), "");
    const RunSpec half = read_run_spec(pulled_box(false, order), "");
    ASSERT_EQ(spec.wall_regions, std::vector<int>{2});
    int wall = 0;
    for (int e = 0; e < spec.mesh.num_tets(); ++e) wall += spec.mesh.region[e] == 2;
    ASSERT_EQ(wall, half.mesh.num_tets());
    EXPECT_EQ(spec.num_points(), spec.points_per_element * wall);
    EXPECT_EQ(spec.num_points(), half.num_points());

    LocalEvaluator points(spec.models, spec.model_of_points());
    Simulation sim(spec, points);
    for (int k = 0; k < sim.points().size(); ++k) ASSERT_EQ(spec.mesh.region[sim.points()[k].element], 2);
    const Field& u = sim.system().field("displacement");
    std::set<int> wall_nodes;
    for (int e = 0; e < spec.mesh.num_tets(); ++e)
      if (spec.mesh.region[e] == 2)
        for (int a : spec.mesh.element_nodes(e)) wall_nodes.insert(a);
    EXPECT_EQ(u.nodes(), std::vector<int>(wall_nodes.begin(), wall_nodes.end()));

    LocalEvaluator half_points(half.models, half.model_of_points());
    Simulation alone(half, half_points);
    const RunResult r = sim.run(), r_alone = alone.run();
    ASSERT_TRUE(r.converged) << r.error;
    ASSERT_TRUE(r_alone.converged) << r_alone.error;
    ASSERT_EQ(r.history.size(), r_alone.history.size());
    for (size_t s = 0; s < r.history.size(); ++s) EXPECT_EQ(r.history[s].iterations, r_alone.history[s].iterations);

    // The same wall, node by node: the DOFs come in the same order, so to round-off.
    std::map<Key, int> node_of;
    for (int a = 0; a < half.mesh.num_nodes(); ++a) node_of[key(half.mesh.nodes[a])] = a;
    const Eigen::VectorXd x = sim.displacement(), y = alone.displacement();
    ASSERT_GT(y.norm(), 1e-3);
    double worst = 0.0;
    for (int a = 0; a < spec.mesh.num_nodes(); ++a) {
      if (!wall_nodes.count(a)) {
        EXPECT_EQ(x.segment<3>(3 * a).norm(), 0.0) << "node " << a << " is off the wall";
        continue;
      }
      const auto it = node_of.find(key(spec.mesh.nodes[a]));
      ASSERT_NE(it, node_of.end());
      worst = std::max(worst, (x.segment<3>(3 * a) - y.segment<3>(3 * it->second)).norm());
    }
    EXPECT_LT(worst, 1e-13 * y.norm()) << "order " << order;
  }
}

void expect_input_error(const json& j, const std::string& where, const std::string& what) {
  try {
    read_run_spec(j, "");
    ADD_FAILURE() << "accepted: " << where;
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(where), std::string::npos) << m;
    EXPECT_NE(m.find(what), std::string::npos) << m;
  }
}

TEST(WallRegions, ASpecThatPutsWallThingsOffTheWallIsRefusedNamingTheKey) {
  json j = pulled_box(true, 1);
  j["mesh"]["wall_regions"] = json::array({3});
  expect_input_error(j, "/mesh/wall_regions/0", "\"3\", which is not in the mesh");
  j["mesh"]["wall_regions"] = json::array({2, "2"});
  expect_input_error(j, "/mesh/wall_regions/1", "twice");
  j["mesh"]["wall_regions"] = json::array();
  expect_input_error(j, "/mesh/wall_regions", "non-empty array");

  j = pulled_box(true, 1);
  j["assign"] = {{"regions", {{"1", "m"}}}};
  expect_input_error(j, "/assign/regions/1", "not in /mesh/wall_regions");
  j = pulled_box(true, 1);
  j["dirichlet"][0]["set"] = "xmin";
  expect_input_error(j, "/dirichlet/0/set", "no node on the wall");
  j = pulled_box(true, 1);
  j["pressure"] = {{{"surface", "ymin"}, {"value", 1.0}}};  // half of it bounds region 1
  expect_input_error(j, "/pressure/0/surface", "not in /mesh/wall_regions");
  j = pulled_box(true, 1);
  j["probes"] = {{"inside_region_1", {0.2, 0.5, 0.5}}};
  expect_input_error(j, "/probes/inside_region_1", "inside the wall");
}

// Every term takes its share from one partition: a surface's triangles go with the tet
// they bound, each to exactly one part.
TEST(MacroPartition, FacesGoWithTheirElementsEachToOnePart) {
  const TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(2, 1, 1), {6, 3, 3});
  const int parts = 3;
  const std::vector<int> part_of = partition_elements(m, parts);
  for (const std::string face : {"zmax", "xmin"}) {
    const auto& tris = m.faces.at(face);
    const std::vector<int> tet = face_elements(m, tris);
    size_t total = 0;
    std::set<std::array<int, 3>> seen;
    for (int p = 0; p < parts; ++p) {
      const MacroPartition mp(p, parts, part_of);
      EXPECT_FALSE(mp.elements().empty());
      const auto owned = mp.owned_faces(m, tris);
      total += owned.size();
      for (const auto& t : owned) {
        EXPECT_TRUE(seen.insert(t).second) << face << ": a triangle in two parts";
        const size_t k = static_cast<size_t>(std::find(tris.begin(), tris.end(), t) - tris.begin());
        EXPECT_TRUE(mp.owns(tet[k]));
        // The tet really has the triangle as a face.
        int shared = 0;
        for (int a : m.tets[tet[k]]) shared += std::count(t.begin(), t.end(), a) > 0;
        EXPECT_EQ(shared, 3);
      }
    }
    EXPECT_EQ(total, tris.size()) << face;
  }
}

// A wall element costs the coordinator (12 DOFs)² on a P1 mesh, an element with no field
// next to nothing: the parts balance the cost, not the element count.
TEST(MacroPartition, PartsBalanceTheCostOfEachElementKind) {
  RunSpec spec = read_run_spec(pulled_box(true, 1), "");
  spec.mesh = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {16, 4, 4}, 0, 2);  // regions 1 | 2 at x = 1/2
  const std::vector<int> w = scene_fields(spec).element_weights(spec.mesh);
  for (int e = 0; e < spec.mesh.num_tets(); ++e) ASSERT_EQ(w[e], spec.mesh.region[e] == 2 ? 144 : 1) << e;
  const int parts = 2;
  const std::vector<int> part = partition_elements(spec.mesh, parts, w);
  std::vector<long> cost(parts, 0), count(parts, 0);
  for (int e = 0; e < spec.mesh.num_tets(); ++e) cost[part[e]] += w[e], ++count[part[e]];
  const double total = static_cast<double>(cost[0] + cost[1]);
  // METIS's default imbalance tolerance is 3 % (ufactor 30); allow for the element grain.
  EXPECT_LT(std::abs(cost[0] - cost[1]) / total, 0.06) << cost[0] << " vs " << cost[1];
  // Half the wall each: the part with more of the cheap region has far more elements.
  EXPECT_GT(std::max(count[0], count[1]), 1.5 * std::min(count[0], count[1]));
  // Without weights the element counts balance instead.
  const std::vector<int> plain = partition_elements(spec.mesh, parts);
  std::vector<long> plain_count(parts, 0);
  for (int p : plain) ++plain_count[p];
  EXPECT_LT(std::abs(plain_count[0] - plain_count[1]), spec.mesh.num_tets() / 10);
}

}  // namespace
}  // namespace fe2
