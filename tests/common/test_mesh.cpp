// Meshes: the box generator, TetMesh checks, the Gmsh reader, the point locator and
// VTU/PVD output.
#include "common/error.h"
#include "common/io/vtu_writer.h"
#include "common/mesh/box_mesh.h"
#include "common/mesh/gmsh_reader.h"
#include "common/mesh/point_locator.h"
#include "common/mesh/regions.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

namespace fe2 {
namespace {

namespace fs = std::filesystem;

std::string data_file(const std::string& name) { return std::string(FE2_SOURCE_DIR) + "/tests/data/" + name; }

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A fresh directory per test (so tests can run concurrently under ctest -j), removed
// when the test ends.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / fmt::format("fe2_{}_{}_{}", info->test_suite_name(), info->name(), getpid());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  fs::path operator/(const std::string& name) const { return path_ / name; }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

void write_text(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// The InputError message of f(), or "" if it does not throw one.
template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

Vec3 normal(const TetMesh& m, const std::array<int, 3>& t) {
  return (m.nodes[t[1]] - m.nodes[t[0]]).cross(m.nodes[t[2]] - m.nodes[t[0]]);
}

Vec3 centroid(const TetMesh& m, const std::array<int, 3>& t) {
  return (m.nodes[t[0]] + m.nodes[t[1]] + m.nodes[t[2]]) / 3.0;
}

Vec3 tet_centroid(const TetMesh& m, int e) {
  Vec3 c = Vec3::Zero();
  for (int n : m.tets[e]) c += m.nodes[n] / 4.0;
  return c;
}

// Every named triangle is a face of its tet with the normal pointing away from the
// tet's remaining node.
void expect_faces_outward(const TetMesh& m) {
  for (const auto& [name, tris] : m.faces)
    for (const auto& t : tris) {
      int owner = -1, opposite = -1;
      for (int e = 0; e < m.num_tets() && owner < 0; ++e) {
        int shared = 0, other = -1;
        for (int n : m.tets[e]) {
          if (std::find(t.begin(), t.end(), n) != t.end())
            ++shared;
          else
            other = n;
        }
        if (shared == 3) {
          owner = e;
          opposite = other;
        }
      }
      ASSERT_GE(owner, 0) << name;
      EXPECT_LT(normal(m, t).dot(m.nodes[opposite] - m.nodes[t[0]]), 0.0) << name;
    }
}

// ---------------------------------------------------------------------------------
// make_box_mesh

const Vec3 kLo(-1.0, 0.0, 0.5), kHi(2.0, 1.0, 3.0);
const std::array<int, 3> kDiv{3, 2, 4};

TEST(BoxMesh, CountsAndPositiveVolumesSumToBox) {
  const TetMesh m = make_box_mesh(kLo, kHi, kDiv);
  EXPECT_EQ(m.num_nodes(), 4 * 3 * 5);
  EXPECT_EQ(m.num_tets(), 6 * 3 * 2 * 4);
  double volume = 0;
  for (int e = 0; e < m.num_tets(); ++e) {
    EXPECT_GT(tet_signed_volume(m, e), 0.0) << "tet " << e;
    volume += tet_signed_volume(m, e);
  }
  EXPECT_NEAR(volume, (kHi - kLo).prod(), 1e-12);
  for (int r : m.region) EXPECT_EQ(r, 1);
}

TEST(BoxMesh, FacesAreOutwardAndCoverTheBox) {
  const TetMesh m = make_box_mesh(kLo, kHi, kDiv);
  const Vec3 centre = (kLo + kHi) / 2, size = kHi - kLo;
  const char* names[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
  ASSERT_EQ(m.faces.size(), 6u);
  for (int d = 0; d < 3; ++d)
    for (int side = 0; side < 2; ++side) {
      const auto& tris = m.faces.at(names[d][side]);
      const int a = (d + 1) % 3, b = (d + 2) % 3;
      EXPECT_EQ(tris.size(), 2u * kDiv[a] * kDiv[b]) << names[d][side];
      double area = 0;
      for (const auto& t : tris) {
        EXPECT_GT(normal(m, t).dot(centroid(m, t) - centre), 0.0) << names[d][side];
        for (int n : t) EXPECT_EQ(m.nodes[n][d], side ? kHi[d] : kLo[d]);
        area += normal(m, t).norm() / 2;
      }
      EXPECT_NEAR(area, size[a] * size[b], 1e-12) << names[d][side];
      // Each face is also a node set of its grid plane.
      EXPECT_EQ(m.node_sets.at(names[d][side]).size(), std::size_t(kDiv[a] + 1) * (kDiv[b] + 1));
    }
  expect_faces_outward(m);
}

TEST(BoxMesh, IsConforming) {
  // Interior faces are shared by exactly two tets; the others are the named faces.
  const TetMesh m = make_box_mesh(kLo, kHi, kDiv);
  std::map<std::array<int, 3>, int> count;
  for (const auto& t : m.tets)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> f{};
      for (int a = 0, k = 0; a < 4; ++a)
        if (a != skip) f[k++] = t[a];
      std::sort(f.begin(), f.end());
      ++count[f];
    }
  std::size_t boundary = 0, named = 0;
  for (const auto& [f, c] : count) {
    EXPECT_LE(c, 2);
    boundary += (c == 1);
  }
  for (const auto& [name, tris] : m.faces) named += tris.size();
  EXPECT_EQ(boundary, named);
}

TEST(BoxMesh, RegionSlabs) {
  const TetMesh m = make_box_mesh(kLo, kHi, kDiv, 2, 2);
  const double mid = (kLo.z() + kHi.z()) / 2;
  int ones = 0;
  for (int e = 0; e < m.num_tets(); ++e) {
    EXPECT_EQ(m.region[e], tet_centroid(m, e).z() < mid ? 1 : 2);
    ones += m.region[e] == 1;
  }
  EXPECT_EQ(2 * ones, m.num_tets());
}

TEST(BoxMesh, RejectsBadArguments) {
  EXPECT_NE(input_error([] { make_box_mesh(kLo, kHi, {0, 1, 1}); }).find("divisions [0, 1, 1]"), std::string::npos);
  EXPECT_NE(input_error([] { make_box_mesh(kHi, kLo, {1, 1, 1}); }).find("make_box_mesh"), std::string::npos);
  EXPECT_NE(input_error([] { make_box_mesh(kLo, kHi, kDiv, 3); }).find("region_slabs_axis 3"), std::string::npos);
  EXPECT_NE(input_error([] { make_box_mesh(kLo, kHi, kDiv, 0, 4); }).find("region_slabs 4"), std::string::npos);
}

// ---------------------------------------------------------------------------------
// validate_mesh and orient_faces_outward

TetMesh unit_tet() {
  TetMesh m;
  m.nodes = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  m.tets = {{0, 1, 2, 3}};
  return m;
}

TEST(TetMesh, ValidateNamesInvertedElement) {
  TetMesh m = unit_tet();
  m.tets[0] = {0, 2, 1, 3};
  const std::string msg = input_error([&] { validate_mesh(m, "beam.msh"); });
  EXPECT_NE(msg.find("mesh 'beam.msh': element 0 (nodes 0 2 1 3) is inverted"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected > 0"), std::string::npos) << msg;
}

TEST(TetMesh, ValidateChecksIndicesAndEmptiness) {
  TetMesh m = unit_tet();
  m.tets[0][3] = 7;
  EXPECT_NE(input_error([&] { validate_mesh(m, "gen"); }).find("node 7"), std::string::npos);
  TetMesh empty;
  EXPECT_NE(input_error([&] { validate_mesh(empty, "gen"); }).find("non-empty"), std::string::npos);
}

TEST(TetMesh, ValidateAddsFaceNodeSetsButKeepsGivenOnes) {
  TetMesh m = unit_tet();
  m.faces["bottom"] = {{0, 2, 1}};
  m.faces["side"] = {{0, 1, 3}};
  m.node_sets["side"] = {3};
  validate_mesh(m, "gen");
  EXPECT_EQ(m.node_sets.at("bottom"), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(m.node_sets.at("side"), (std::vector<int>{3}));
  EXPECT_EQ(m.region, (std::vector<int>{1}));
}

TEST(TetMesh, OrientFlipsInwardFacesAndRejectsNonFaces) {
  TetMesh m = unit_tet();
  m.faces["bottom"] = {{0, 1, 2}};  // normal +z points into the tet
  orient_named_surfaces(m, "gen");
  EXPECT_LT(normal(m, m.faces["bottom"][0]).z(), 0.0);
  m.nodes.push_back(Vec3(1, 1, 1));
  m.faces["stray"] = {{1, 2, 4}};
  const std::string msg = input_error([&] { orient_named_surfaces(m, "gen"); });
  EXPECT_NE(msg.find("face 'stray' triangle 0 (nodes 1 2 4) is not a face"), std::string::npos) << msg;
}

// ---------------------------------------------------------------------------------
// Gmsh reader

TEST(GmshReader, ReadsTwoTetsWithNamedGroups) {
  const TetMesh m = read_gmsh_tets(data_file("two_tets.msh"));
  EXPECT_EQ(m.num_nodes(), 5);  // node 99 belongs to no tet
  ASSERT_EQ(m.num_tets(), 2);
  EXPECT_EQ(m.tets[0], (std::array<int, 4>{0, 1, 2, 3}));
  EXPECT_EQ(m.tets[1], (std::array<int, 4>{1, 2, 3, 4}));
  EXPECT_EQ(m.nodes[4], Vec3(1, 1, 1));
  EXPECT_EQ(m.region, (std::vector<int>{7, 1}));
  EXPECT_EQ(m.region_names, (std::map<int, std::string>{{7, "muscle"}}));
  ASSERT_EQ(m.faces.size(), 2u);  // the unnamed surface is not kept
  ASSERT_EQ(m.faces.at("base").size(), 1u);
  ASSERT_EQ(m.faces.at("lid").size(), 1u);
  EXPECT_LT(normal(m, m.faces.at("base")[0]).z(), 0.0);  // flipped from the file's +z
  expect_faces_outward(m);
  EXPECT_EQ(m.node_sets.at("apex"), (std::vector<int>{0}));
  EXPECT_EQ(m.node_sets.at("edge"), (std::vector<int>{0, 1}));
  EXPECT_EQ(m.node_sets.at("base"), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(m.node_sets.at("lid"), (std::vector<int>{1, 2, 4}));
}

TEST(GmshReader, InvertedTetNamesLineAndTags) {
  const std::string file = data_file("inverted_tet.msh");
  const std::string msg = input_error([&] { read_gmsh_tets(file); });
  EXPECT_NE(msg.find("inverted"), std::string::npos) << msg;
  EXPECT_NE(msg.find(file + "' line 23: element 1 (node tags 1 3 2 4)"), std::string::npos) << msg;
}

TEST(GmshReader, MissingFileIsNamed) {
  const std::string msg = input_error([] { read_gmsh_tets("/nonexistent/heart.msh"); });
  EXPECT_NE(msg.find("cannot open mesh file '/nonexistent/heart.msh'"), std::string::npos) << msg;
}

TEST(GmshReader, RejectsVersion22AndBinary) {
  const std::string msg = input_error([] { read_gmsh_tets(data_file("tet_v22.msh")); });
  EXPECT_NE(msg.find("tet_v22.msh' line 2: MeshFormat 2.2, expected 4.1 ASCII"), std::string::npos) << msg;

  const ScratchDir dir;
  const fs::path bin = dir / "binary.msh";
  write_text(bin, "$MeshFormat\n4.1 1 8\n\x01\x00\x00\x00\n$EndMeshFormat\n");
  const std::string bmsg = input_error([&] { read_gmsh_tets(bin.string()); });
  EXPECT_NE(bmsg.find("binary"), std::string::npos) << bmsg;
}

TEST(GmshReader, ReportsUnknownNodeWithLine) {
  std::string text = slurp(data_file("two_tets.msh"));
  text.replace(text.find("7 12 13 14 15"), 13, "7 12 13 14 16");
  const ScratchDir dir;
  const fs::path file = dir / "bad_node.msh";
  write_text(file, text);
  const std::string msg = input_error([&] { read_gmsh_tets(file.string()); });
  EXPECT_NE(msg.find("line 60: element 7 uses node tag 16"), std::string::npos) << msg;
}

// Two tets sharing the face of node tags 2 3 4: tet 1 (tags 1 2 3 4) in physical volume 7
// "left", tet 2 (tags 2 3 4 5) in `right_tag`; the triangles of physical surface 8
// "septum" as node tags (tag n is node n - 1).
std::string two_region_msh(int right_tag, const std::vector<std::array<int, 3>>& septum) {
  std::string text = fmt::format(
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
      "$PhysicalNames\n3\n2 8 \"septum\"\n3 7 \"left\"\n3 {0} \"right\"\n$EndPhysicalNames\n"
      "$Entities\n0 0 1 2\n1 0 0 0 1 1 1 1 8 0\n1 0 0 0 1 1 1 1 7 0\n2 0 0 0 1 1 1 1 {0} 0\n$EndEntities\n"
      "$Nodes\n1 5 1 5\n3 1 0 5\n1\n2\n3\n4\n5\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n$EndNodes\n"
      "$Elements\n3 {1} 1 {1}\n2 1 2 {2}\n",
      right_tag, septum.size() + 2, septum.size());
  int tag = 1;
  for (const auto& t : septum) text += fmt::format("{} {} {} {}\n", tag++, t[0], t[1], t[2]);
  text += fmt::format("3 1 4 1\n{} 1 2 3 4\n3 2 4 1\n{} 2 3 4 5\n$EndElements\n", tag, tag + 1);
  return text;
}

TEST(GmshReader, NamedInteriorSurfaceIsAnInterfaceFromTheLowerRegion) {
  const ScratchDir dir;
  write_text(dir / "septum.msh", two_region_msh(1, {{2, 3, 4}}));
  const TetMesh m = read_gmsh_tets((dir / "septum.msh").string());
  EXPECT_EQ(m.region, (std::vector<int>{7, 1}));
  EXPECT_EQ(m.faces.count("septum"), 0u);
  ASSERT_EQ(m.interfaces.count("septum"), 1u);
  const auto& tris = m.interfaces.at("septum");
  ASSERT_EQ(tris.size(), 1u);
  std::array<int, 3> sorted = tris[0];
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, (std::array<int, 3>{1, 2, 3}));
  // From region 1 (tet 1, on the far side from the origin) into region 7 (tet 0): the
  // file's normal (1, 1, 1) is flipped.
  EXPECT_LT(normal(m, tris[0]).dot(Vec3(1, 1, 1)), 0.0);
  EXPECT_EQ(m.node_sets.at("septum"), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(interface_nodes(m, "septum"), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(interface_nodes(m, std::vector<int>{1}, std::vector<int>{7}), (std::vector<int>{1, 2, 3}));
  const std::string msg = input_error([&] { interface_nodes(m, "wall"); });
  EXPECT_NE(msg.find("interface 'wall': the mesh has none of that name, expected one of its interfaces (septum)"),
            std::string::npos)
      << msg;
}

TEST(GmshReader, InterfaceWithinOneRegionIsOrientedFromTheFirstTet) {
  const ScratchDir dir;
  write_text(dir / "one_region.msh", two_region_msh(7, {{2, 4, 3}}));
  const TetMesh m = read_gmsh_tets((dir / "one_region.msh").string());
  EXPECT_EQ(m.region, (std::vector<int>{7, 7}));
  ASSERT_EQ(m.interfaces.at("septum").size(), 1u);
  // Out of tet 0, the one at the origin: the file's normal −(1, 1, 1) is flipped.
  EXPECT_GT(normal(m, m.interfaces.at("septum")[0]).dot(Vec3(1, 1, 1)), 0.0);
}

TEST(GmshReader, NamedTriangleOffTheMeshOrHalfInsideIsRefused) {
  const ScratchDir dir;
  const std::string off = (dir / "off.msh").string(), half = (dir / "half.msh").string();
  write_text(off, two_region_msh(1, {{1, 2, 5}}));
  std::string msg = input_error([&] { read_gmsh_tets(off); });
  EXPECT_NE(msg.find("mesh '" + off + "': face 'septum' triangle 0 (nodes 0 1 4) is not a face of any "
                     "tetrahedron, expected a boundary face of the volume mesh or an interior face "
                     "between two of its tetrahedra"),
            std::string::npos)
      << msg;
  write_text(half, two_region_msh(1, {{2, 3, 4}, {1, 2, 3}}));
  msg = input_error([&] { read_gmsh_tets(half); });
  EXPECT_NE(msg.find("mesh '" + half + "': face 'septum' has boundary triangle 1 and interior triangle 0, "
                     "expected a surface wholly on the boundary or wholly inside (an interface)"),
            std::string::npos)
      << msg;
}

TEST(GmshReader, NoTetsInHexFile) {
  const std::string msg = input_error([] { read_gmsh_tets(data_file("two_hexes.msh")); });
  EXPECT_NE(msg.find("no 4-node tetrahedra"), std::string::npos) << msg;
}

// Garbage must end in an InputError (or a valid mesh), never a crash or another exception.
TEST(GmshReader, TruncatedOrCorruptedFilesNeverCrash) {
  const std::string text = slurp(data_file("two_tets.msh"));
  const ScratchDir dir;
  const fs::path file = dir / "garbage.msh";
  const auto read_ok_or_input_error = [&](const std::string& contents) {
    write_text(file, contents);
    try {
      read_gmsh_tets(file.string());
    } catch (const InputError&) {
    }
  };
  for (std::size_t n = 0; n < text.size(); n += 3) {
    SCOPED_TRACE(n);
    EXPECT_NO_THROW(read_ok_or_input_error(text.substr(0, n)));
  }
  std::mt19937 rng(12345);
  const std::string alphabet = "0123456789-.e $\"\n\t\x01\xff";
  for (int trial = 0; trial < 300; ++trial) {
    std::string bad = text;
    for (int k = 0; k < 3; ++k) bad[rng() % bad.size()] = alphabet[rng() % alphabet.size()];
    SCOPED_TRACE(trial);
    EXPECT_NO_THROW(read_ok_or_input_error(bad));
  }
}

TEST(GmshReader, ReadsHexesWithSortedRegions) {
  const HexMesh h = read_gmsh_hexes(data_file("two_hexes.msh"));
  EXPECT_EQ(h.num_nodes(), 12);
  ASSERT_EQ(h.num_hexes(), 2);
  EXPECT_EQ(h.hexes[0], (std::array<int, 8>{0, 1, 4, 3, 6, 7, 10, 9}));
  EXPECT_EQ(h.region, (std::vector<int>{1, 0}));  // physical tags 5 and 2 -> sorted [2, 5]
  // Region names are the physical names, so unit materials are assigned by name.
  EXPECT_EQ(h.region_names, (std::vector<std::string>{"matrix", "cell"}));
  EXPECT_EQ(h.lo, Vec3(0, 0, 0));
  EXPECT_EQ(h.hi, Vec3(2, 1, 1));
  EXPECT_DOUBLE_EQ(h.volume(), 2.0);
}

// An unnamed physical volume is named by its tag, as regions of macro meshes are.
TEST(GmshReader, HexRegionWithoutNameIsNamedByTag) {
  std::string text = slurp(data_file("two_hexes.msh"));
  const std::string names = "$PhysicalNames\n2\n3 5 \"cell\"\n";
  text.replace(text.find(names), names.size(), "$PhysicalNames\n1\n");
  const ScratchDir dir;
  write_text(dir / "unnamed.msh", text);
  const HexMesh h = read_gmsh_hexes((dir / "unnamed.msh").string());
  EXPECT_EQ(h.region_names, (std::vector<std::string>{"matrix", "5"}));
}

// A hex volume entity in no physical group has no material: refused, naming the entity.
TEST(GmshReader, HexEntityWithoutPhysicalGroupIsRefused) {
  std::string text = slurp(data_file("two_hexes.msh"));
  const std::string entity2 = "2 1 0 0 2 1 1 1 2 0";  // volume 2 in physical group 2
  text.replace(text.find(entity2), entity2.size(), "2 1 0 0 2 1 1 0 0");
  const ScratchDir dir;
  write_text(dir / "untagged.msh", text);
  const std::string msg = input_error([&] { read_gmsh_hexes((dir / "untagged.msh").string()); });
  EXPECT_NE(msg.find("untagged.msh' line 47: hexahedra of volume entity 2 (elements 2..2) belong "
                     "to no physical group"),
            std::string::npos)
      << msg;
}

// ---------------------------------------------------------------------------------
// locate_point

TEST(LocatePoint, BarycentricsReproduceInteriorPoints) {
  const TetMesh m = make_box_mesh(kLo, kHi, kDiv);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec3 X = kLo + (kHi - kLo).cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
    const MeshPoint p = locate_point(m, X);
    ASSERT_GE(p.tet, 0);
    Vec3 Y = Vec3::Zero();
    double sum = 0;
    for (int a = 0; a < 4; ++a) {
      EXPECT_GE(p.bary[a], 0.0);
      Y += p.bary[a] * m.nodes[m.tets[p.tet][a]];
      sum += p.bary[a];
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    EXPECT_LT((Y - X).norm(), 1e-12);
  }
  EXPECT_NO_THROW(locate_point(m, kHi));  // a corner
}

TEST(LocatePoint, SnapsWithinToleranceAndRejectsOutside) {
  const TetMesh m = make_box_mesh(kLo, kHi, kDiv);
  const MeshPoint p = locate_point(m, Vec3(kHi.x() + 1e-12, 0.5, 1.0));
  for (double b : p.bary) EXPECT_GE(b, 0.0);
  const std::string msg = input_error([&] { locate_point(m, Vec3(2.5, 0.5, 1.0)); });
  EXPECT_NE(msg.find("point (2.5, 0.5, 1)"), std::string::npos) << msg;
}

// ---------------------------------------------------------------------------------
// VTU / PVD output

TEST(VtuWriter, WritesTetMeshWithFields) {
  const TetMesh m = make_box_mesh(kLo, kHi, kDiv);
  VtuFields points, cells;
  points.add_vector("u", std::vector<Vec3>(m.num_nodes(), Vec3(1, 2, 3)));
  points.add_scalar("p", std::vector<double>(m.num_nodes(), 0.25));
  Vec9 P;
  P << 1, 2, 3, 4, 5, 6, 7, 8, 9;  // column-major: P(0,1) = 4
  cells.add_tensor("P", std::vector<Vec9>(m.num_tets(), P));
  const ScratchDir dir;
  const fs::path file = dir / "box.vtu";
  write_vtu(file.string(), m, points, cells);
  const std::string text = slurp(file.string());
  EXPECT_NE(text.find("<VTKFile type=\"UnstructuredGrid\""), std::string::npos);
  EXPECT_NE(text.find("NumberOfPoints=\"60\" NumberOfCells=\"144\""), std::string::npos);
  EXPECT_NE(text.find("Name=\"P\" NumberOfComponents=\"9\""), std::string::npos);
  EXPECT_NE(text.find(" 1 4 7 2 5 8 3 6 9\n"), std::string::npos);  // row-major for VTK
  EXPECT_NE(text.find("Name=\"region\""), std::string::npos);
  EXPECT_NE(text.find("</VTKFile>"), std::string::npos);
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
}

TEST(VtuWriter, WritesHexMesh) {
  const HexMesh h = read_gmsh_hexes(data_file("two_hexes.msh"));
  const ScratchDir dir;
  const fs::path file = dir / "unit.vtu";
  write_vtu(file.string(), h);
  const std::string text = slurp(file.string());
  EXPECT_NE(text.find("NumberOfPoints=\"12\" NumberOfCells=\"2\""), std::string::npos);
  EXPECT_NE(text.find(" 12 12\n"), std::string::npos);  // cell types
}

TEST(VtuWriter, PvdCollectionIsRewrittenEachStep) {
  const ScratchDir dir;
  PvdWriter pvd((dir / "run.pvd").string());
  EXPECT_NE(slurp(pvd.path()).find("<Collection>"), std::string::npos);
  pvd.add(0.0, (dir / "step_0.vtu").string());
  pvd.add(0.5, (dir / "vtu/step_1.vtu").string());
  const std::string text = slurp(pvd.path());
  EXPECT_NE(text.find("timestep=\"0\" group=\"\" part=\"0\" file=\"step_0.vtu\""), std::string::npos) << text;
  EXPECT_NE(text.find("timestep=\"0.5\" group=\"\" part=\"0\" file=\"vtu/step_1.vtu\""), std::string::npos) << text;
  EXPECT_FALSE(fs::exists(pvd.path() + ".tmp"));
}

TEST(VtuWriter, UnwritableDirectoryIsInputError) {
  const TetMesh m = make_box_mesh(kLo, kHi, {1, 1, 1});
  const std::string msg = input_error([&] { write_vtu("/nonexistent/dir/out.vtu", m); });
  EXPECT_NE(msg.find("/nonexistent/dir/out.vtu.tmp"), std::string::npos) << msg;
}

}  // namespace
}  // namespace fe2
