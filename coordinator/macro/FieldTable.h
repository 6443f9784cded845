#pragma once
// The macro unknowns as data. Each field (wall displacement ū, pressure p, cavity
// pressures p_c, later fluid velocity and mesh motion) is one block of the macro system
// (MFEM's block offsets: one contiguous range per field, in declaration order), and says
// where its unknowns live, how it advances in time and how its residual is measured:
//
//   field            space       components  time       residual norm
//   displacement     nodal (P1/P2)     3     Newmark-β  ‖R‖ / max(‖f_int‖, ‖f_ext‖)
//   pressure         P1 (or P1+P0)     1     none       ‖R‖ / ‖∫N_p‖ (a volume)
//   cavity_pressure  global            1     none       max_c |R_c| / V_c,ref
//
// A nodal field numbers its unknowns node-major (offset + components·a + i) over the
// nodes of its elements in ascending order; a field over the whole mesh thus has the
// DOF offset + 3a + i at node a. Terms look fields up by name (MacroTerm::declare) and
// never compute an offset themselves.
#include "common/mesh/TetMesh.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace fe2 {

/// The finite-element space a field's unknowns belong to.
enum class FieldSpace {
  nodal,         ///< every node of its elements (P1 or P2, the mesh's order)
  vertex,        ///< the vertices of its elements (P1 on a linear or quadratic mesh)
  vertex_element,///< P1+P0: the vertices, then one constant per element but the first
                 ///< (whose constant is the P1 constant less the others')
  global,        ///< a few scalars tied to no mesh entity (cavity pressures, multipliers)
};

/// How a field advances in time (coordinator/macro/TimeIntegration.h).
enum class TimeScheme {
  none,           ///< no rate: pressures, multipliers, a quasi-static displacement
  newmark,        ///< second order in time: Newmark-β (β, γ of the spec)
  backward_euler, ///< first order in time: v = (x − x_n)/Δt
  bdf2,           ///< first order in time, BDF2: v from x, x_n, x_{n−1} (second-order accurate)
};

/// How the convergence test measures a field's residual R (on its free equations).
enum class ResidualNorm {
  relative_to_load,  ///< ‖R‖ / max(‖f_int‖, ‖f_ext‖, ‖s‖) over the field: forces (s: a floor)
  scaled_l2,         ///< ‖R‖ / ‖s‖, s the scale its terms report (MacroTerm::add_residual_scale)
  scaled_max,        ///< max_i |R_i| / s_i
};

struct FieldDecl {
  std::string name;
  int components = 1;
  FieldSpace space = FieldSpace::nodal;
  std::vector<int> regions;  ///< region tags of its elements (TetMesh::region); empty: all
  int count = 0;             ///< global fields: how many scalars
  TimeScheme time = TimeScheme::none;
  ResidualNorm norm = ResidualNorm::relative_to_load;
  double rtol = 1e-8;        ///< converged when its residual norm is at most this
};

/// A declared field with its numbering (FieldTable::number).
class Field {
 public:
  const FieldDecl& decl() const { return decl_; }
  const std::string& name() const { return decl_.name; }
  int id() const { return id_; }
  int components() const { return decl_.components; }
  /// The field's block: DOFs [offset, offset + size).
  int offset() const { return offset_; }
  int size() const { return size_; }
  bool contains(int dof) const { return dof >= offset_ && dof < offset_ + size_; }
  /// Whether the field has unknowns on elements of region `tag` (global fields: none).
  bool lives_on(int tag) const;

  /// Mesh nodes carrying unknowns (nodal and vertex spaces), ascending.
  const std::vector<int>& nodes() const { return nodes_; }
  /// Whether the field has unknowns at mesh node `node`.
  bool has_node(int node) const { return node >= 0 && node < static_cast<int>(index_of_node_.size()) && index_of_node_[node] >= 0; }
  /// DOF of component i at mesh node `node` (throws fe2::Error if it has none there).
  int node_dof(int node, int i = 0) const;
  /// DOFs of all components at each of `nodes`, node-major (the element's footprint).
  std::vector<int> node_dofs(const std::vector<int>& nodes) const;
  /// P1+P0: DOF of element e's constant, or −1 (the first element, or no constants).
  int element_dof(int e) const;
  /// Global fields: DOF of scalar k.
  int global_dof(int k) const;
  /// A nodal field's values at every one of `num_nodes` mesh nodes, node-major
  /// (components·a + i), zero at nodes it does not live on; from the full vector `x`.
  Eigen::VectorXd at_every_node(const Eigen::VectorXd& x, int num_nodes) const;

 private:
  friend class FieldTable;
  FieldDecl decl_;
  int id_ = 0, offset_ = 0, size_ = 0;
  std::vector<int> nodes_;
  std::vector<int> index_of_node_;  ///< node -> position in nodes_, or −1
  std::vector<int> constant_of_element_;  ///< P1+P0: element -> its constant's position, or −1
};

class FieldTable {
 public:
  /// Declares a field (names are unique); returns its id. Before number().
  int add(FieldDecl decl);
  /// Numbers every field's unknowns on `mesh`, in declaration order.
  void number(const TetMesh& mesh);
  bool numbered() const { return numbered_; }

  int size() const { return static_cast<int>(fields_.size()); }
  const Field& operator[](int id) const { return fields_[id]; }
  /// The field named `name`; throws fe2::Error naming the fields there are otherwise.
  const Field& at(const std::string& name) const;
  /// The field named `name`, or null.
  const Field* find(const std::string& name) const;
  /// The field a DOF belongs to.
  const Field& field_of(int dof) const;
  int num_dofs() const { return num_dofs_; }
  /// Per element of `mesh`: the cost of its macro assembly, (Σ over the fields living on
  /// it of their DOFs on the element)², for a partition balanced by work (METIS weights).
  std::vector<int> element_weights(const TetMesh& mesh) const;
  std::vector<Field>::const_iterator begin() const { return fields_.begin(); }
  std::vector<Field>::const_iterator end() const { return fields_.end(); }

 private:
  std::vector<Field> fields_;
  int num_dofs_ = 0;
  bool numbered_ = false;
};

}  // namespace fe2
