#include "common/mesh/box_mesh.h"

#include "common/error.h"
#include "common/mesh/kuhn_split.h"

#include <climits>
#include <cmath>

namespace fe2 {

namespace {

constexpr const char* kSource = "make_box_mesh";
constexpr const char* kFaceNames[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};

using Corner = std::array<int, 3>;  // 0/1 offsets of a cell corner along x, y, z

void check_arguments(const Vec3& lo, const Vec3& hi, const std::array<int, 3>& n, int axis,
                     int slabs) {
  for (int a = 0; a < 3; ++a) {
    if (n[a] < 1)
      throw InputError(fmt::format("{}: divisions [{}, {}, {}]: expected every entry >= 1", kSource,
                                   n[0], n[1], n[2]));
    if (!(std::isfinite(lo[a]) && std::isfinite(hi[a]) && hi[a] > lo[a]))
      throw InputError(fmt::format("{}: box from ({}, {}, {}) to ({}, {}, {}): expected finite "
                                   "corners with hi > lo along every axis",
                                   kSource, lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z()));
  }
  if (6.0 * (n[0] + 1.0) * (n[1] + 1.0) * (n[2] + 1.0) > INT_MAX)
    throw InputError(fmt::format("{}: divisions [{}, {}, {}] give too many elements, expected fewer "
                                 "than {} tetrahedra",
                                 kSource, n[0], n[1], n[2], INT_MAX));
  if (axis < -1 || axis > 2)
    throw InputError(fmt::format("{}: region_slabs_axis {}: expected -1 (one region), 0, 1 or 2", kSource, axis));
  if (axis >= 0 && (slabs < 1 || slabs > n[axis]))
    throw InputError(fmt::format("{}: region_slabs {}: expected 1 <= slabs <= divisions[{}] = {}", kSource,
                                 slabs, axis, n[axis]));
}

// Grid coordinate i of n along one axis; the last plane is exactly hi so that
// boundary faces are exactly planar.
double grid_coord(double lo, double hi, int i, int n) { return i == n ? hi : lo + (hi - lo) * i / n; }

}  // namespace

TetMesh make_box_mesh(const Vec3& lo, const Vec3& hi, std::array<int, 3> n, int region_slabs_axis,
                      int region_slabs, int order) {
  check_arguments(lo, hi, n, region_slabs_axis, region_slabs);
  if (order != 1 && order != 2)
    throw InputError(fmt::format("{}: order {}: expected 1 (4-node) or 2 (10-node tetrahedra)", kSource, order));
  const auto node_id = [&](int i, int j, int k) { return i + (n[0] + 1) * (j + (n[1] + 1) * k); };

  TetMesh m;
  m.nodes.resize(static_cast<std::size_t>(n[0] + 1) * (n[1] + 1) * (n[2] + 1));
  for (int k = 0; k <= n[2]; ++k)
    for (int j = 0; j <= n[1]; ++j)
      for (int i = 0; i <= n[0]; ++i)
        m.nodes[node_id(i, j, k)] = Vec3(grid_coord(lo.x(), hi.x(), i, n[0]), grid_coord(lo.y(), hi.y(), j, n[1]),
                                         grid_coord(lo.z(), hi.z(), k, n[2]));

  const auto kuhn = kuhn_tets();
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const Corner cell{i, j, k};
        const int region = region_slabs_axis < 0
                               ? 1
                               : 1 + static_cast<int>(static_cast<long long>(cell[region_slabs_axis]) *
                                                      region_slabs / n[region_slabs_axis]);
        for (const auto& corners : kuhn) {
          std::array<Corner, 4> g;  // grid indices of the tet's nodes
          for (int a = 0; a < 4; ++a)
            for (int d = 0; d < 3; ++d) g[a][d] = cell[d] + corners[a][d];
          m.tets.push_back({node_id(g[0][0], g[0][1], g[0][2]), node_id(g[1][0], g[1][1], g[1][2]),
                            node_id(g[2][0], g[2][1], g[2][2]), node_id(g[3][0], g[3][1], g[3][2])});
          m.region.push_back(region);
          // A tet face whose three nodes share a boundary grid plane is a boundary face.
          const auto& t = m.tets.back();
          for (int opp = 0; opp < 4; ++opp) {
            std::array<int, 3> face_nodes{}, local{};
            for (int a = 0, f = 0; a < 4; ++a)
              if (a != opp) {
                local[f] = a;
                face_nodes[f++] = t[a];
              }
            for (int d = 0; d < 3; ++d)
              for (int side = 0; side < 2; ++side) {
                const int plane = side * n[d];
                if (g[local[0]][d] == plane && g[local[1]][d] == plane && g[local[2]][d] == plane)
                  m.faces[kFaceNames[d][side]].push_back(face_nodes);
              }
          }
        }
      }

  orient_named_surfaces(m, kSource);
  if (order == 2) make_quadratic(m);
  validate_mesh(m, kSource);
  return m;
}

}  // namespace fe2
