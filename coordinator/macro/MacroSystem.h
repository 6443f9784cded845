#pragma once
// The macro unknowns and the fixed triplet pattern of S̄ (Eq. 10) over several fields.
// The fields (FieldTable.h) number the unknowns, one block per field; the constraints
// (Constraints.h) number the equations: prescribed DOFs have none, tied DOFs share their
// master's.
//
// Macro terms (MacroTerm.h) declare the local matrices they fill — an element's or a
// face's dense footprint, rows and columns a DOF list each; the pattern is their union
// (one triplet per entry), in a fixed order, so each iteration only refills values.
// With several coordinators each declares the local matrices of its own elements (MUMPS
// distributed assembled input sums duplicates).
#include "coordinator/macro/Constraints.h"
#include "coordinator/macro/FieldTable.h"

#include <Eigen/Dense>

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace fe2 {

class MacroSystem {
 public:
  /// Numbers `fields` on `mesh` and closes `constraints` over them.
  MacroSystem(const TetMesh& mesh, FieldTable fields, MacroConstraints constraints);

  // --- unknowns
  const FieldTable& fields() const { return fields_; }
  const Field& field(const std::string& name) const { return fields_.at(name); }
  int num_dofs() const { return fields_.num_dofs(); }

  // --- equations
  const MacroConstraints& constraints() const { return constraints_; }
  int num_free() const { return constraints_.num_free(); }
  /// Row equation of a DOF, or −1 (prescribed, following); a tied DOF has its master's.
  int eq(int dof) const { return constraints_.eq(dof); }
  /// Column equation of a DOF, or −1 (prescribed); tied and following DOFs have their master's.
  int column(int dof) const { return constraints_.column(dof); }
  /// Prescribed DOFs and their value at time t.
  const std::vector<int>& prescribed() const { return constraints_.prescribed(); }
  double prescribed_value(size_t k, double t) const { return constraints_.prescribed_value(k, t); }

  // --- pattern
  /// Declares a square local matrix over `dofs`; returns its id. Before the first rows() call.
  int declare_local(std::vector<int> dofs);
  /// A rectangular local matrix: rows `row_dofs`, columns `col_dofs` (a cavity's border).
  int declare_local(std::vector<int> row_dofs, std::vector<int> col_dofs);
  const std::vector<int>& local_rows(int local) const { return locals_[local].rows; }
  const std::vector<int>& local_cols(int local) const { return locals_[local].cols; }
  /// The pattern (0-based rows/cols of free equations), all local matrices in declaration order.
  const std::vector<int>& rows() const { return rows_; }
  const std::vector<int>& cols() const { return cols_; }
  /// Adds K (local rows x local columns) into `values` at the local matrix's slots.
  void add(int local, const Eigen::MatrixXd& K, std::vector<double>& values) const;

 private:
  struct Local {
    std::vector<int> rows, cols;
    size_t first_slot = 0;  ///< into slot_
  };
  FieldTable fields_;
  MacroConstraints constraints_;
  std::vector<Local> locals_;
  std::vector<int> slot_;               ///< per local entry (row-major): slot or −1
  std::vector<int> rows_, cols_;
  std::unordered_map<uint64_t, int> slot_of_entry_;  ///< (row << 32 | col) -> slot
};

}  // namespace fe2
