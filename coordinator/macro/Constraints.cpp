#include "coordinator/macro/Constraints.h"

#include "common/error.h"

namespace fe2 {

int MacroConstraints::add_value(Value g) {
  values_.push_back(std::move(g));
  return static_cast<int>(values_.size()) - 1;
}

void MacroConstraints::prescribe(int dof, int source) {
  FE2_CHECK(source >= 0 && source < static_cast<int>(values_.size()), "no value source {}", source);
  prescriptions_.emplace_back(dof, source);
}

void MacroConstraints::tie(int dof, int master, double offset) {
  FE2_CHECK(dof != master, "DOF {} tied to itself", dof);
  tie_requests_.push_back({dof, master, offset, true});
}

void MacroConstraints::follow(int dof, int master, double offset) {
  FE2_CHECK(dof != master, "DOF {} follows itself", dof);
  tie_requests_.push_back({dof, master, offset, false});
}

void MacroConstraints::close(int num_dofs) {
  FE2_CHECK(eq_.empty(), "the constraints are closed once");
  std::vector<int> source(num_dofs, -1), master(num_dofs, -1);
  std::vector<double> offset(num_dofs, 0.0);
  std::vector<char> shares(num_dofs, 1);
  for (const auto& [dof, s] : prescriptions_) {
    FE2_CHECK(dof >= 0 && dof < num_dofs, "prescribed DOF {} of {}", dof, num_dofs);
    source[dof] = s;
  }
  for (const Tie& t : tie_requests_) {
    FE2_CHECK(t.dof >= 0 && t.dof < num_dofs && t.master >= 0 && t.master < num_dofs, "tie {} -> {} of {} DOFs",
              t.dof, t.master, num_dofs);
    if (source[t.dof] >= 0) continue;  // prescribed wins
    master[t.dof] = t.master;
    offset[t.dof] = t.offset;
    shares[t.dof] = t.shares_equation;
  }
  // Each DOF's root: follow its ties (a chain longer than the DOF count is a cycle).
  root_.assign(num_dofs, -1);
  std::vector<double> total(num_dofs, 0.0);
  std::vector<char> row_kept(num_dofs, 1);  // every link of the chain shares its equation
  for (int d = 0; d < num_dofs; ++d) {
    int r = d, steps = 0;
    double c = 0.0;
    while (master[r] >= 0) {
      c += offset[r];
      row_kept[d] &= shares[r];
      r = master[r];
      if (++steps > num_dofs)
        throw InputError(fmt::format("the ties of macro DOF {} form a cycle: no DOF of it is free", d));
    }
    root_[d] = r;
    total[d] = c;
  }
  eq_.assign(num_dofs, -1);
  column_.assign(num_dofs, -1);
  for (int d = 0; d < num_dofs; ++d) {
    const int r = root_[d];
    if (source[r] >= 0) {
      prescribed_.push_back(d);
      prescribed_source_.emplace_back(source[r], total[d]);
    } else if (r == d) {
      eq_[d] = column_[d] = num_free_++;
    }
  }
  for (int d = 0; d < num_dofs; ++d)
    if (root_[d] != d && source[root_[d]] < 0) {
      column_[d] = eq_[root_[d]];
      if (row_kept[d]) eq_[d] = column_[d];
      ties_.push_back({d, root_[d], total[d], static_cast<bool>(row_kept[d])});
    }
}

double MacroConstraints::prescribed_value(size_t k, double t) const {
  const auto& [s, c] = prescribed_source_[k];
  const double g = values_[s](t);
  return c == 0.0 ? g : g + c;
}

}  // namespace fe2
