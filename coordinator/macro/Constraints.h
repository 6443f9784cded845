#pragma once
// Constraints on the macro unknowns, in one place (after deal.II's AffineConstraints):
//   prescribed   x_d = g(t)              a Dirichlet value, a ramp, any function of time
//   tie          x_d = x_m + c           a shared interface node, a field equal to another
//                                        field's value there, a periodic pair
// Applied by numbering the equations: a prescribed DOF has none (its value is lifted to
// the right-hand side, MacroAssembly::set_lift); a tied DOF shares its master's equation,
// so that its residual adds to the master's and its column to the master's column (the
// condensation C ᵀ R, C ᵀ K C of a unit-weight tie, assembled without a product).
// Chains resolve to their root: a DOF tied to a prescribed one is prescribed, g(t) + c.
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
  /// x_dof = x_master + offset (a later tie of the same DOF replaces an earlier one; a
  /// prescription wins over a tie).
  void tie(int dof, int master, double offset = 0.0);

  /// Resolves ties and numbers the free equations in DOF order; throws fe2::InputError
  /// on a cycle of ties. @p num_dofs: every field's DOFs (FieldTable::num_dofs).
  void close(int num_dofs);

  int num_free() const { return num_free_; }
  /// Equation of a DOF: its own (a master), its root's (tied), or −1 (prescribed).
  int eq(int dof) const { return eq_[dof]; }
  /// True if `dof` holds its own equation (free and not tied).
  bool is_master(int dof) const { return eq_[dof] >= 0 && root_[dof] == dof; }
  /// Prescribed DOFs, ascending, and their value at time t.
  const std::vector<int>& prescribed() const { return prescribed_; }
  double prescribed_value(size_t k, double t) const;
  /// Tied DOFs (ascending) with their root master and offset.
  struct Tie {
    int dof, master;
    double offset;
  };
  const std::vector<Tie>& ties() const { return ties_; }
  /// Sets every tied DOF of x to its master's value plus the offset.
  template <class Vector>
  void distribute(Vector& x) const {
    for (const Tie& t : ties_) x[t.dof] = x[t.master] + t.offset;
  }

 private:
  std::vector<Value> values_;
  std::vector<std::pair<int, int>> prescriptions_;   ///< (dof, source), in call order
  std::vector<Tie> tie_requests_;                    ///< in call order
  std::vector<int> eq_, root_;
  std::vector<int> prescribed_;
  std::vector<std::pair<int, double>> prescribed_source_;  ///< (source, offset) per prescribed DOF
  std::vector<Tie> ties_;
  int num_free_ = 0;
};

}  // namespace fe2
