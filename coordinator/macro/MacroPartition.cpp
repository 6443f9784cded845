#include "coordinator/macro/MacroPartition.h"

#include "common/error.h"

namespace fe2 {

MacroPartition MacroPartition::whole(const TetMesh& mesh) {
  return MacroPartition(0, 1, std::vector<int>(static_cast<size_t>(mesh.num_tets()), 0));
}

MacroPartition::MacroPartition(int part, int parts, std::vector<int> part_of_element)
    : part_(part), parts_(parts), part_of_element_(std::move(part_of_element)) {
  FE2_CHECK(parts >= 1 && part >= 0 && part < parts, "part {} of {}", part, parts);
  for (size_t e = 0; e < part_of_element_.size(); ++e)
    if (part_of_element_[e] == part_) elements_.push_back(static_cast<int>(e));
}

std::vector<std::array<int, 3>> MacroPartition::owned_faces(const TetMesh& mesh,
                                                            const std::vector<std::array<int, 3>>& tris) const {
  const std::vector<int> tet = face_elements(mesh, tris);
  std::vector<std::array<int, 3>> out;
  for (size_t k = 0; k < tris.size(); ++k)
    if (owns(tet[k])) out.push_back(tris[k]);
  return out;
}

}  // namespace fe2
