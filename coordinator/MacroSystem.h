#pragma once
// The macro unknowns and the fixed triplet pattern of S̄ (Eq. 10) over several fields:
//   [ ū : 3 per mesh node (node-major 3a + i) | p : 1 per vertex, when the formulation
//     has a pressure field, then 1 per element but the first for an enriched P1+P0
//     pressure | p_c : 1 per cavity coupled to a circulation | later: fluid ]
// each field a contiguous range at its offset (MFEM's BlockOperator offsets). Dirichlet
// DOFs of ū are eliminated: free DOFs get equation numbers, in DOF order.
//
// Macro terms (MacroTerm.h) declare the local blocks they fill, a DOF list each; the
// pattern is their union (one triplet per entry), in a fixed order, so each iteration
// only refills values.
// With several coordinators each declares the blocks of its own elements (MUMPS
// distributed assembled input sums duplicates).
#include "common/mesh/TetMesh.h"
#include "coordinator/RunSpec.h"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace fe2 {

class MacroSystem {
 public:
  /// `pressure_field`: a P1 pressure on the vertices (enriched by a constant per
  /// element if spec.formulation.element_pressure) follows the displacement block.
  MacroSystem(const RunSpec& spec, bool pressure_field);

  // --- fields
  int num_dofs() const { return num_dofs_; }
  int displacement_dofs() const { return 3 * num_nodes_; }
  bool has_pressure() const { return !pressure_of_node_.empty(); }
  int pressure_offset() const { return 3 * num_nodes_; }
  /// All pressure unknowns: the vertices', then the elements' (enriched pressure).
  int num_pressure() const { return num_vertex_pressures() + num_element_pressures_; }
  int num_vertex_pressures() const { return static_cast<int>(vertex_of_pressure_.size()); }
  /// DOF of the pressure at mesh node `node` (a vertex).
  int pressure_dof(int node) const { return pressure_offset() + pressure_of_node_[node]; }
  /// DOF of element e's constant pressure, or −1: none (P1 pressure, or the first
  /// element, whose constant is the P1 constant less the others' and would make the
  /// pressure field's basis linearly dependent).
  int element_pressure_dof(int e) const {
    return e > 0 && num_element_pressures_ > 0 ? pressure_offset() + num_vertex_pressures() + e - 1 : -1;
  }
  /// Mesh node of pressure unknown j.
  int vertex_of_pressure(int j) const { return vertex_of_pressure_[j]; }
  /// Cavity pressures (RunSpec::coupled_cavities order), after the pressure field.
  int num_cavities() const { return num_cavities_; }
  int cavity_dof(int c) const { return pressure_offset() + num_pressure() + c; }

  // --- equations
  int num_free() const { return num_free_; }
  /// Equation of a DOF, or −1 if prescribed.
  int eq(int dof) const { return eq_[dof]; }
  /// Prescribed DOFs and their value at time t.
  const std::vector<int>& prescribed() const { return prescribed_; }
  double prescribed_value(size_t k, double t) const;

  // --- pattern
  /// Declares a local block over `dofs`; returns its id. Before the first rows() call.
  int declare_block(std::vector<int> dofs);
  /// A rectangular block: rows `row_dofs`, columns `col_dofs` (a cavity's border).
  int declare_block(std::vector<int> row_dofs, std::vector<int> col_dofs);
  const std::vector<int>& block_rows(int block) const { return blocks_[block].rows; }
  const std::vector<int>& block_cols(int block) const { return blocks_[block].cols; }
  /// The pattern (0-based rows/cols of free equations), all blocks in declaration order.
  const std::vector<int>& rows() const { return rows_; }
  const std::vector<int>& cols() const { return cols_; }
  /// Adds K (block rows x block columns) into `values` at the block's slots.
  void add(int block, const Eigen::MatrixXd& K, std::vector<double>& values) const;

 private:
  struct Block {
    std::vector<int> rows, cols;
    size_t first_slot = 0;  ///< into slot_
  };
  const RunSpec& spec_;
  int num_nodes_;
  int num_dofs_;
  int num_cavities_ = 0;
  int num_element_pressures_ = 0;
  int num_free_ = 0;
  std::vector<int> eq_;
  std::vector<int> prescribed_;
  std::vector<std::pair<int, int>> prescribed_source_;  ///< (dirichlet index, component)
  std::vector<int> pressure_of_node_;   ///< node -> pressure unknown (−1: not a vertex)
  std::vector<int> vertex_of_pressure_;
  std::vector<Block> blocks_;
  std::vector<int> slot_;               ///< per block entry (row-major): slot or −1
  std::vector<int> rows_, cols_;
  std::unordered_map<uint64_t, int> slot_of_entry_;  ///< (row << 32 | col) -> slot
};

}  // namespace fe2
