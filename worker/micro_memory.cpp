#include "worker/micro_memory.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace fe2 {

namespace {

// Bytes per item, from the containers in MicroModel and MicroUnit (see the header).
constexpr double kPerElementModel = 1600.0   // HexGeometry (at most: equal shapes share one)
                                    + 288.0  // scatter: 72 ints
                                    + 96.0   // equations: 24 ints
                                    + 36.0   // hex nodes and region
                                    + 3456.0;  // transient pattern lists (576 ints, grown)
constexpr double kPerNodeModel = 24.0 + 16.0;   // coordinates; periodic map and ρ
constexpr double kPerNonzeroModel = 12.0 + 16.0;  // pattern (index + value); triplets
constexpr double kPerDofUnit = 8.0 * 48.0;        // vectors, χ, G, H and their copies
constexpr double kPerNonzeroUnit = 3 * 8.0 + 4.0; // K, K at refresh, K committed; indices
constexpr double kPerFactorEntry = 10.0;          // value + supernodal index share (measured)
// Calibration of the nested-dissection fill model against CHOLMOD (METIS ordering,
// supernodal, relaxed amalgamation; two_cells units): CHOLMOD's xsize over the model's
// count is 0.90 (8×4×4), 0.87 (16×4×4), 2.0 (8³), 1.35 (12³), 1.29 (16³), 1.07 (21³:
// 31 M vs 29 M). This factor makes the estimate an upper bound, ≈ 1.1–2.5× CHOLMOD.
constexpr double kFillCalibration = 2.2;
constexpr long long kLeafNodes = 64;  // boxes this small are eliminated densely

// Entries of L for eliminating a box of d[0]×d[1]×d[2] nodes (3 DOF each) whose faces
// touch `boundary` nodes numbered after it. Nested dissection cuts the longest axis:
// one plane of nodes, or two on a periodic axis (a ring needs two cuts), eliminated
// last and dense, coupled to the box's boundary; each half inherits half the boundary
// plus the separator, capped by its surface.
double nd_fill(std::array<long long, 3> d, std::array<bool, 3> periodic, double boundary) {
  const double n = static_cast<double>(d[0]) * d[1] * d[2];
  if (n <= 0) return 0.0;
  if (n <= kLeafNodes) {
    const double s = 3.0 * n;
    return 0.5 * s * (s + 1) + s * 3.0 * boundary;
  }
  const int a = static_cast<int>(std::max_element(d.begin(), d.end()) - d.begin());
  const double plane = n / d[a];
  const long long cuts = periodic[a] ? 2 : 1;
  const long long rest = std::max<long long>(0, d[a] - cuts);
  const double s = 3.0 * plane * std::min<long long>(cuts, d[a]);
  const double top = 0.5 * s * (s + 1) + s * 3.0 * boundary;
  if (rest == 0) return top;
  periodic[a] = false;
  auto child = [&](long long h) {
    std::array<long long, 3> c = d;
    c[a] = h;
    const double surface = 2.0 * (static_cast<double>(c[0]) * c[1] + static_cast<double>(c[1]) * c[2] +
                                  static_cast<double>(c[0]) * c[2]);
    return nd_fill(c, periodic, std::min(0.5 * boundary + cuts * plane, surface));
  };
  const long long h1 = rest / 2, h2 = rest - h1;
  if (h1 == h2) return top + 2.0 * child(h1);  // halves alike: one recursion, O(log n) calls
  return top + (h1 > 0 ? child(h1) : 0.0) + child(h2);
}

}  // namespace

double fill_entries(std::array<long long, 3> cells) {
  for (auto& c : cells) c = std::max<long long>(c, 1);
  const double n = 3.0 * cells[0] * cells[1] * cells[2];
  // Never more than the dense lower triangle.
  return std::min(0.5 * n * (n + 1), kFillCalibration * nd_fill(cells, {true, true, true}, 0.0));
}

MicroMemoryEstimate estimate_micro_memory(std::array<long long, 3> cells, long long nodes,
                                          long long elements, bool lu, bool single, bool half) {
  MicroMemoryEstimate m;
  m.nodes = nodes;
  m.elements = elements;
  m.dofs = std::max<long long>(3 * elements - 3, 3);  // one periodic node per hex on a grid
  m.pattern_nnz = std::min(81.0 * m.dofs, static_cast<double>(m.dofs) * m.dofs);
  m.factor_entries = fill_entries(cells) * (lu ? 2.0 : 1.0);
  m.model_bytes = kPerElementModel * elements + kPerNodeModel * nodes + kPerNonzeroModel * m.pattern_nnz;
  m.factor_bytes = kPerFactorEntry * m.factor_entries * (!single ? 1.0 : half && !lu ? 0.25 : 0.5);
  m.unit_bytes = kPerDofUnit * m.dofs + kPerNonzeroUnit * m.pattern_nnz + m.factor_bytes;
  return m;
}

std::string format_bytes(double b) {
  if (b < 1e3) return fmt::format("{:.0f} B", b);
  if (b < 1e6) return fmt::format("{:.1f} kB", b / 1e3);
  if (b < 1e9) return fmt::format("{:.1f} MB", b / 1e6);
  if (b < 1e12) return fmt::format("{:.1f} GB", b / 1e9);
  return fmt::format("{:.1f} TB", b / 1e12);
}

std::string MicroMemoryEstimate::describe() const {
  return fmt::format("{} DOF, K {:.3g} M nonzeros, factor ≈ {:.3g} M entries: model {} + {} per unit",
                     dofs, pattern_nnz / 1e6, factor_entries / 1e6, format_bytes(model_bytes),
                     format_bytes(unit_bytes));
}

}  // namespace fe2
