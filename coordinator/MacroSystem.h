#pragma once
// Macro unknowns and the fixed triplet pattern of S̄ (Eq. 10): equation numbers of
// free DOFs (Dirichlet DOFs are eliminated), one 12x12 block per owned tet and one 9x9
// block per owned pressure triangle, in a fixed order so each iteration only refills
// values. With several coordinators each holds the triplets of its own elements
// (MUMPS distributed assembled input sums them).
#include "common/mesh/TetMesh.h"
#include "coordinator/RunSpec.h"

#include <vector>

namespace fe2 {

class MacroSystem {
 public:
  /// `owned_tets`: this coordinator's tets; pressure triangles k with k % parts == part.
  MacroSystem(const RunSpec& spec, const std::vector<int>& owned_tets, int part = 0, int parts = 1);

  int num_dofs() const { return 3 * num_nodes_; }
  int num_free() const { return num_free_; }
  /// Equation of DOF 3a + i, or -1 if prescribed.
  int eq(int dof) const { return eq_[dof]; }
  /// Prescribed DOFs and their value at time t.
  const std::vector<int>& prescribed() const { return prescribed_; }
  double prescribed_value(size_t k, double t) const;

  /// The pattern (0-based rows/cols of free equations).
  const std::vector<int>& rows() const { return rows_; }
  const std::vector<int>& cols() const { return cols_; }
  /// Adds the k-th owned tet's 12x12 block (node-major) into `values` at its slots.
  void add_tet(int k, const Eigen::Matrix<double, 12, 12>& Ke, std::vector<double>& values) const;
  /// Adds pressure triangle `k` (in the order of pressure_triangles()) block.
  void add_triangle(int k, const Eigen::Matrix<double, 9, 9>& Ke, std::vector<double>& values) const;
  struct PressureTriangle {
    std::array<int, 3> nodes;
    int load;  ///< index into spec.pressure
  };
  const std::vector<PressureTriangle>& pressure_triangles() const { return triangles_; }

 private:
  const RunSpec& spec_;
  int num_nodes_;
  int num_free_ = 0;
  std::vector<int> eq_;
  std::vector<int> prescribed_;
  std::vector<std::pair<int, int>> prescribed_source_;  ///< (dirichlet index, component)
  std::vector<PressureTriangle> triangles_;
  std::vector<int> rows_, cols_;
  std::vector<int> tet_map_;        ///< per tet 144 entries: slot or -1
  std::vector<int> tri_map_;        ///< per triangle 81 entries: slot or -1
};

}  // namespace fe2
