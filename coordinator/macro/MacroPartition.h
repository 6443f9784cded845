#pragma once
// Which part of the macro mesh this coordinator assembles (paper Eq. 12: each element
// belongs to exactly one coordinator, whatever its region). Every term takes its share
// from here: the elements it integrates over, the boundary faces of those elements
// (a face goes with the tet it bounds), and the global unknowns' rows (cavity volumes,
// multipliers), which the first coordinator assembles. MUMPS sums the distributed input.
#include "common/mesh/TetMesh.h"

#include <array>
#include <vector>

namespace fe2 {

class MacroPartition {
 public:
  /// The whole mesh on one part.
  static MacroPartition whole(const TetMesh& mesh);
  /// Part `part` of `parts`, `part_of_element` giving each element's part.
  MacroPartition(int part, int parts, std::vector<int> part_of_element);

  int part() const { return part_; }
  int parts() const { return parts_; }
  bool owns(int element) const { return part_of_element_[static_cast<size_t>(element)] == part_; }
  /// This part's elements, ascending.
  const std::vector<int>& elements() const { return elements_; }
  /// The triangles of `tris` whose tet this part owns, in the order given (boundary
  /// faces; an interface triangle goes with the tet of the lower region tag).
  std::vector<std::array<int, 3>> owned_faces(const TetMesh& mesh,
                                              const std::vector<std::array<int, 3>>& tris) const;
  /// Whether this part assembles the rows of global unknowns (exactly one does).
  bool owns_globals() const { return part_ == 0; }

 private:
  int part_ = 0, parts_ = 1;
  std::vector<int> part_of_element_;
  std::vector<int> elements_;
};

}  // namespace fe2
