#include "worker/micro_cell.h"

#include "common/error.h"

#include <cmath>
#include <vector>

namespace fe2 {

int num_regions(const CellLayout& layout) { return layout.kind == "homogeneous" ? 1 : 2; }

namespace {

int classify(const CellLayout& c, const Vec3& x) {
  if (c.kind == "homogeneous") return 0;
  if (c.kind == "laminate") return x[c.axis] < c.fraction * c.size[c.axis] ? 0 : 1;
  // two_cells: along axis 1 each half [0, L/2) and [L/2, L) holds one cell centred in it.
  const double half = 0.5 * c.size[0];
  const double s = std::fmod(x[0], half) / half;          // position within the half, 0..1
  const double g = c.gap * c.size[0] / half;              // gap as a fraction of a half
  const bool along = s > 0.5 * g && s < 1.0 - 0.5 * g;
  bool across = true;
  for (int d = 1; d < 3; ++d) {
    const double t = x[d] / c.size[d];
    across = across && std::abs(t - 0.5) < 0.5 * c.cross_section;
  }
  return along && across ? 1 : 0;
}

}  // namespace

HexMesh make_cell_mesh(const CellLayout& c) {
  const auto [n1, n2, n3] = c.resolution;
  HexMesh m;
  m.lo = Vec3::Zero();
  m.hi = c.size;
  auto node_id = [&](int i, int j, int k) { return i + (n1 + 1) * (j + (n2 + 1) * k); };
  m.nodes.reserve(static_cast<size_t>(n1 + 1) * (n2 + 1) * (n3 + 1));
  for (int k = 0; k <= n3; ++k)
    for (int j = 0; j <= n2; ++j)
      for (int i = 0; i <= n1; ++i)
        m.nodes.emplace_back(c.size[0] * i / n1, c.size[1] * j / n2, c.size[2] * k / n3);
  std::vector<int> count(num_regions(c), 0);
  for (int k = 0; k < n3; ++k)
    for (int j = 0; j < n2; ++j)
      for (int i = 0; i < n1; ++i) {
        m.hexes.push_back({node_id(i, j, k), node_id(i + 1, j, k), node_id(i + 1, j + 1, k),
                           node_id(i, j + 1, k), node_id(i, j, k + 1), node_id(i + 1, j, k + 1),
                           node_id(i + 1, j + 1, k + 1), node_id(i, j + 1, k + 1)});
        const Vec3 centroid(c.size[0] * (i + 0.5) / n1, c.size[1] * (j + 0.5) / n2,
                            c.size[2] * (k + 0.5) / n3);
        m.region.push_back(classify(c, centroid));
        ++count[m.region.back()];
      }
  for (size_t r = 0; r < count.size(); ++r)
    if (count[r] == 0)
      throw InputError(fmt::format(
          "micro cell '{}' at resolution [{}, {}, {}] has no element in region {} ({}); "
          "expected a finer resolution or a larger {}",
          c.kind, n1, n2, n3, r, c.kind == "two_cells" ? (r ? "cell" : "ecm") : (r ? "b" : "a"),
          c.kind == "two_cells" ? "gap / cross_section" : "fraction"));
  return m;
}

}  // namespace fe2
