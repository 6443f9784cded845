#pragma once
// Constraints on the macro unknowns, in one place (after deal.II's AffineConstraints):
//   prescribed  x_d = g(t)       a Dirichlet value, a ramp, any function of time
//   tie         x_d = x_m + c    one unknown shared by two fields (fluid and wall velocity
//                                on the interface), a periodic pair: d's equation adds to
//                                m's, so the two fields' forces balance there
//   follow      x_d = x_m + c    d takes m's value and drops its own equation (the mesh
//                                motion equal to the wall's displacement on the interface:
//                                the wall does not feel the mesh)
// Applied by numbering: every DOF has a row equation (its residual's, −1 if it has none)
// and a column equation (the unknown its tangent entries multiply, −1 if prescribed).
// A master has its own for both; a tied DOF its master's for both (the condensation
// Cᵀ R, Cᵀ K C of a unit-weight tie, assembled without a product); a following DOF no row
// and its master's column; a prescribed DOF neither (its value is lifted to the
// right-hand side, MacroAssembly::set_lift).
// Chains resolve to their root: a DOF tied or following a prescribed one is prescribed,
// g(t) + c.
#include <functional>
#include <vector>

namespace fe2 {

class MacroConstraints {
 public:
  using Value = std::function<double(double t)>;

  /// A value source several DOFs may share (one per Dirichlet condition and component).
  int add_value(Value g);
  /// x_dof = g_source(t); a later prescription of the same DOF replaces an earlier one.
  void prescribe(int dof, int source);
  /// x_dof = x_master + offset, the equations summed (a later tie or follow of the same
  /// DOF replaces an earlier one; a prescription wins over both).
  void tie(int dof, int master, double offset = 0.0);
  /// x_dof = x_master + offset, dof's own equation dropped.
  void follow(int dof, int master, double offset = 0.0);

  /// Resolves ties and numbers the free equations in DOF order; throws fe2::InputError
  /// on a cycle of ties. @p num_dofs: every field's DOFs (FieldTable::num_dofs).
  void close(int num_dofs);

  int num_free() const { return num_free_; }
  /// Row equation of a DOF: its own (a master), its root's (tied), or −1 (prescribed,
  /// following).
  int eq(int dof) const { return eq_[dof]; }
  /// Column equation of a DOF: its own (a master), its root's (tied, following), or −1
  /// (prescribed).
  int column(int dof) const { return column_[dof]; }
  /// True if `dof` holds its own equation (free and not tied).
  bool is_master(int dof) const { return eq_[dof] >= 0 && root_[dof] == dof; }
  /// Prescribed DOFs, ascending, and their value at time t.
  const std::vector<int>& prescribed() const { return prescribed_; }
  double prescribed_value(size_t k, double t) const;
  /// Tied and following DOFs (ascending) with their root master and offset.
  struct Tie {
    int dof, master;
    double offset;
    bool shares_equation;  ///< tie (true) or follow (false)
  };
  const std::vector<Tie>& ties() const { return ties_; }
  /// Sets every tied or following DOF of x to its master's value plus the offset.
  template <class Vector>
  void distribute(Vector& x) const {
    for (const Tie& t : ties_) x[t.dof] = x[t.master] + t.offset;
  }

 private:
  std::vector<Value> values_;
  std::vector<std::pair<int, int>> prescriptions_;   ///< (dof, source), in call order
  std::vector<Tie> tie_requests_;                    ///< in call order
  std::vector<int> eq_, column_, root_;
  std::vector<int> prescribed_;
  std::vector<std::pair<int, double>> prescribed_source_;  ///< (source, offset) per prescribed DOF
  std::vector<Tie> ties_;
  int num_free_ = 0;
};

}  // namespace fe2
