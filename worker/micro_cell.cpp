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

CellResolution cell_resolution(const CellLayout& c) {
  CellResolution r;
  if (c.kind == "homogeneous") return r;
  const auto [n1, n2, n3] = c.resolution;
  long long in_region_1 = 0;
  for (int k = 0; k < n3; ++k)
    for (int j = 0; j < n2; ++j)
      for (int i = 0; i < n1; ++i)
        in_region_1 += classify(c, Vec3(c.size[0] * (i + 0.5) / n1, c.size[1] * (j + 0.5) / n2,
                                        c.size[2] * (k + 0.5) / n3));
  r.realised = static_cast<double>(in_region_1) / (static_cast<double>(n1) * n2 * n3);
  // Interfaces at these fractions of each axis; n resolves them when n·t is whole.
  std::array<std::vector<double>, 3> interfaces;
  if (c.kind == "laminate") {
    r.nominal = 1.0 - c.fraction;
    interfaces[c.axis] = {c.fraction};
  } else {  // two_cells: each half of axis 1 holds a cell of length L1/2 − gap·L1
    r.nominal = (1.0 - 2.0 * c.gap) * c.cross_section * c.cross_section;
    interfaces[0] = {0.5, 0.5 * c.gap, 0.5 - 0.5 * c.gap};
    interfaces[1] = interfaces[2] = {0.5 - 0.5 * c.cross_section, 0.5 + 0.5 * c.cross_section};
  }
  for (int d = 0; d < 3; ++d) {
    r.exact[d] = 0;
    for (int n = 1; n <= 1000 && r.exact[d] == 0; ++n) {
      bool whole = true;
      for (double t : interfaces[d]) whole = whole && std::abs(n * t - std::round(n * t)) < 1e-9 * n;
      if (whole) r.exact[d] = n;
    }
  }
  return r;
}

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
