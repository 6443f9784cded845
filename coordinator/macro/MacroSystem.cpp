#include "coordinator/macro/MacroSystem.h"

namespace fe2 {

MacroSystem::MacroSystem(const TetMesh& mesh, FieldTable fields, MacroConstraints constraints)
    : fields_(std::move(fields)), constraints_(std::move(constraints)) {
  if (!fields_.numbered()) fields_.number(mesh);
  constraints_.close(fields_.num_dofs());
}

int MacroSystem::declare_local(std::vector<int> dofs) {
  std::vector<int> cols = dofs;
  return declare_local(std::move(dofs), std::move(cols));
}

int MacroSystem::declare_local(std::vector<int> row_dofs, std::vector<int> col_dofs) {
  Local b;
  b.first_slot = slot_.size();
  for (int r : row_dofs)
    for (int c : col_dofs) {
      const int er = eq(r), ec = column(c);
      if (er < 0 || ec < 0) {
        slot_.push_back(-1);
        continue;
      }
      // One triplet per matrix entry on this process: local matrices of neighbouring
      // elements and of several terms share it (MUMPS then gets an assembled pattern,
      // about a tenth of the element-by-element triplets for P2 meshes).
      const auto [it, added] = slot_of_entry_.try_emplace(
          (static_cast<uint64_t>(er) << 32) | static_cast<uint32_t>(ec), static_cast<int>(rows_.size()));
      if (added) {
        rows_.push_back(er);
        cols_.push_back(ec);
      }
      slot_.push_back(it->second);
    }
  b.rows = std::move(row_dofs);
  b.cols = std::move(col_dofs);
  locals_.push_back(std::move(b));
  return static_cast<int>(locals_.size()) - 1;
}

void MacroSystem::add(int local, const Eigen::MatrixXd& K, std::vector<double>& values) const {
  const Local& b = locals_[local];
  const int nr = static_cast<int>(b.rows.size()), nc = static_cast<int>(b.cols.size());
  const int* slot = &slot_[b.first_slot];
  for (int r = 0; r < nr; ++r)
    for (int c = 0; c < nc; ++c)
      if (slot[nc * r + c] >= 0) values[slot[nc * r + c]] += K(r, c);
}

}  // namespace fe2
