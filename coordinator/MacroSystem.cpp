#include "coordinator/MacroSystem.h"

namespace fe2 {

MacroSystem::MacroSystem(const RunSpec& spec, bool pressure_field)
    : spec_(spec), num_nodes_(spec.mesh.num_nodes()) {
  const TetMesh& m = spec.mesh;
  if (pressure_field) {
    pressure_of_node_.assign(num_nodes_, -1);
    vertex_of_pressure_ = m.vertices();
    for (size_t j = 0; j < vertex_of_pressure_.size(); ++j)
      pressure_of_node_[vertex_of_pressure_[j]] = static_cast<int>(j);
    if (spec.formulation.element_pressure) num_element_pressures_ = m.num_tets() - 1;
  }
  num_cavities_ = static_cast<int>(spec.coupled_cavities.size());
  num_dofs_ = 3 * num_nodes_ + num_pressure() + num_cavities_;
  // Prescribed DOFs; a later condition on the same DOF overrides an earlier one.
  std::vector<int> source(num_dofs_, -1);
  for (size_t d = 0; d < spec.dirichlet.size(); ++d)
    for (int node : m.node_sets.at(spec.dirichlet[d].set))
      for (int i = 0; i < 3; ++i)
        if (spec.dirichlet[d].fixed[i]) source[3 * node + i] = static_cast<int>(d);
  eq_.assign(num_dofs_, -1);
  for (int dof = 0; dof < num_dofs_; ++dof) {
    if (source[dof] >= 0) {
      prescribed_.push_back(dof);
      prescribed_source_.emplace_back(source[dof], dof % 3);
    } else {
      eq_[dof] = num_free_++;
    }
  }
}

double MacroSystem::prescribed_value(size_t k, double t) const {
  const auto [d, i] = prescribed_source_[k];
  const DirichletSpec& ds = spec_.dirichlet[d];
  return ds.value[i] * ramp_factor(ds.ramp, t, spec_.t_end);
}

int MacroSystem::declare_block(std::vector<int> dofs) {
  std::vector<int> cols = dofs;
  return declare_block(std::move(dofs), std::move(cols));
}

int MacroSystem::declare_block(std::vector<int> row_dofs, std::vector<int> col_dofs) {
  Block b;
  b.first_slot = slot_.size();
  for (int r : row_dofs)
    for (int c : col_dofs) {
      const int er = eq_[r], ec = eq_[c];
      if (er < 0 || ec < 0) {
        slot_.push_back(-1);
        continue;
      }
      // One triplet per matrix entry on this process: blocks of neighbouring elements
      // and of several terms share it (MUMPS then gets an assembled pattern, about a
      // tenth of the element-by-element triplets for P2 meshes).
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
  blocks_.push_back(std::move(b));
  return static_cast<int>(blocks_.size()) - 1;
}

void MacroSystem::add(int block, const Eigen::MatrixXd& K, std::vector<double>& values) const {
  const Block& b = blocks_[block];
  const int nr = static_cast<int>(b.rows.size()), nc = static_cast<int>(b.cols.size());
  const int* slot = &slot_[b.first_slot];
  for (int r = 0; r < nr; ++r)
    for (int c = 0; c < nc; ++c)
      if (slot[nc * r + c] >= 0) values[slot[nc * r + c]] += K(r, c);
}

}  // namespace fe2
