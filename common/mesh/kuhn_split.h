#pragma once
// The Kuhn (Freudenthal) split of the unit cube into 6 tets, one per permutation p of
// the axes, along the path 000 -> e_p0 -> e_p0 + e_p1 -> 111. A tet's volume has the
// sign of p, so odd permutations swap nodes 1 and 2 to come out positive. The same
// diagonal in every cell keeps a structured grid conforming (box and LV generators).
#include <array>
#include <utility>

namespace fe2 {

using GridOffset = std::array<int, 3>;  ///< 0/1 offsets of a cell corner along the grid axes

inline std::array<std::array<GridOffset, 4>, 6> kuhn_tets() {
  constexpr int perms[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  std::array<std::array<GridOffset, 4>, 6> tets{};
  for (int t = 0; t < 6; ++t) {
    GridOffset c{0, 0, 0};
    tets[t][0] = c;
    for (int s = 0; s < 3; ++s) {
      c[perms[t][s]] = 1;
      tets[t][s + 1] = c;
    }
    if (t >= 3) std::swap(tets[t][1], tets[t][2]);
  }
  return tets;
}

}  // namespace fe2
