#include "coordinator/macro/MacroProblem.h"

#include "common/error.h"
#include "coordinator/agree_on_failure.h"
#include "coordinator/macro/field_residuals.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace fe2 {

MacroProblem::MacroProblem(const RunSpec& spec, const proto::Group& group, MacroSystem system)
    : spec_(spec),
      group_(group),
      system_(std::move(system)),
      time_integration_(spec.beta, spec.gamma),
      solver_(group, system_.num_free(), spec.macro_solver) {
  const int n = system_.num_dofs();
  x_ = v_ = a_ = Eigen::VectorXd::Zero(n);
  system_.constraints().distribute(x_);  // ties with an offset hold from the start
  x_n_ = x_nm1_ = x_;
  v_n_ = v_;
  a_n_ = a_;
  t_n_ = spec.t_start;
  prescribed_value_ = [this](int k, double t) { return system_.prescribed_value(k, t); };
}

void MacroProblem::set_initial(
    const std::function<void(const FieldTable&, Eigen::VectorXd& x, Eigen::VectorXd& v)>& initial) {
  initial(system_.fields(), x_, v_);
  system_.constraints().distribute(x_);
  x_n_ = x_nm1_ = x_;
  v_n_ = v_;
}

void MacroProblem::add_term(std::unique_ptr<MacroTerm> term) {
  FE2_CHECK(!pattern_set_, "macro term '{}' added after the first solve", term->name());
  terms_.push_back(std::move(term));
}

Eigen::VectorXd MacroProblem::field_values(const std::string& name) const {
  const Field& f = system_.field(name);
  return x_.segment(f.offset(), f.size());
}

Eigen::VectorXd MacroProblem::prescribed_increment(double t_new) const {
  Eigen::VectorXd du_D = Eigen::VectorXd::Zero(system_.num_dofs());
  const auto& prescribed = system_.prescribed();
  for (size_t k = 0; k < prescribed.size(); ++k)
    du_D[prescribed[k]] = prescribed_value_(static_cast<int>(k), t_new) - x_n_[prescribed[k]];
  return du_D;
}

void MacroProblem::predict(double dt) {
  for (const Field& f : system_.fields()) time_integration_.rates(f, dt, x_, x_n_, v_n_, a_n_, x_nm1_, dt_n_, v_, a_);
}

MacroState MacroProblem::state(double t_new, double dt) const {
  MacroState s{x_, v_, a_, t_new, dt, {}};
  for (const Field& f : system_.fields()) s.rates.push_back(time_integration_.coefficients(f, dt, dt_n_));
  return s;
}

void MacroProblem::prepare() {
  if (pattern_set_) return;
  for (auto& term : terms_) term->declare(system_);
  values_.assign(system_.rows().size(), 0.0);
  solver_.set_pattern(system_.rows(), system_.cols());
  assembly_ = std::make_unique<MacroAssembly>(system_, values_);
  for (const Field& f : system_.fields()) {
    Eigen::VectorXd scale = Eigen::VectorXd::Zero(f.size());
    for (const auto& term : terms_) term->add_residual_scale(f, scale);
    group_.allreduce_sum(scale.data(), static_cast<int>(scale.size()));
    residual_scales_.push_back(std::move(scale));
  }
  pattern_set_ = true;
}

void MacroProblem::assemble(double t_new, double dt, const Eigen::VectorXd* lift) {
  FE2_CHECK(pattern_set_, "MacroProblem::assemble before prepare()");
  assembly_->clear();
  assembly_->set_lift(lift);
  const MacroState s = state(t_new, dt);
  std::string why;
  fluid_assembly_seconds_ = 0.0;
  try {
    for (auto& term : terms_) {
      const auto start = std::chrono::steady_clock::now();
      term->assemble(s, *assembly_);
      if (term->physics() == MacroTerm::Physics::fluid)
        fluid_assembly_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
  } catch (const NumericalError& e) {
    why = e.what();
  }
  agree_on_failure(group_, why);
  assembly_->set_lift(nullptr);
}

std::vector<double> MacroProblem::residual_norms(double t_new) {
  Eigen::VectorXd& f_int = assembly_->internal();
  Eigen::VectorXd& f_ext = assembly_->external();
  group_.allreduce_sum(f_int.data(), static_cast<int>(f_int.size()));
  group_.allreduce_sum(f_ext.data(), static_cast<int>(f_ext.size()));
  std::vector<double> norms = field_residual_norms(system_, f_int, f_ext, residual_scales_);
  for (const Field& f : system_.fields())
    if (!std::isfinite(norms[f.id()]))
      throw NumericalError(fmt::format("non-finite macro residual of field '{}' at t = {:.6g}", f.name(), t_new));
  return norms;
}

// S̄ Δx = −R̃ on the coordinators (summed on the MUMPS host), Δx to all.
void MacroProblem::solve(bool quasi_static_first) {
  du_ = assembly_->rhs();
  group_.reduce_sum(du_.data(), system_.num_free(), 0);
  try {
    solver_.solve(values_, du_);
  } catch (const SingularMatrixError& e) {
    // The enriched pressure is inf–sup stable only where elements have free vertices
    // (Boffi et al. 2012): say so, it is the likelier cause then.
    const std::string why =
        std::string(e.what()) +
        (spec_.formulation.element_pressure
             ? "; or the enriched pressure (formulation.pressure 'P1+P0'): elements whose vertices "
               "are all prescribed leave pressure modes free (refine there, or use 'P1')"
             : "");
    // Quasi-static iteration 1 assembles at the committed state (points have no rate
    // dependence yet): the same matrix whatever the step, so no cut-back can help.
    if (quasi_static_first)
      throw SingularMatrixError(why + "; it is the matrix of the last converged state, so cutting "
                                "the step back cannot help",
                                true);
    throw SingularMatrixError(why, e.at_committed_state);
  }
  group_.bcast(du_.data(), system_.num_free(), 0);
}

void MacroProblem::update(bool first, const Eigen::VectorXd& du_D) {
  if (!std::all_of(du_.begin(), du_.end(), [](double x) { return std::isfinite(x); }))
    throw NumericalError("non-finite macro correction Δx");
  x_k_ = x_;
  for (int dof = 0; dof < system_.num_dofs(); ++dof)
    if (system_.column(dof) >= 0) x_[dof] += du_[system_.column(dof)];
  if (first) x_ += du_D;
  system_.constraints().distribute(x_);  // tied and following DOFs exactly at their master's value
}

void MacroProblem::retract(double alpha, bool first, const Eigen::VectorXd& du_D) {
  FE2_CHECK(x_k_.size() == x_.size(), "MacroProblem::retract before update");
  x_ = x_k_;
  for (int dof = 0; dof < system_.num_dofs(); ++dof)
    if (system_.column(dof) >= 0) x_[dof] += alpha * du_[system_.column(dof)];
  if (first) x_ += du_D;
  system_.constraints().distribute(x_);
}

std::vector<double> MacroProblem::correction_norms(double alpha) const {
  std::vector<double> norms;
  for (const Field& f : system_.fields()) {
    double m = 0.0;
    for (int dof = f.offset(); dof < f.offset() + f.size(); ++dof)
      if (const int col = system_.column(dof); col >= 0) m = std::max(m, std::abs(alpha * du_[col]));
    norms.push_back(m);
  }
  return norms;
}

bool MacroProblem::accept(double t_new, double dt) {
  const MacroState s = state(t_new, dt);
  bool all = true;
  for (auto& term : terms_) all = term->accept(s) && all;
  return all;
}

void MacroProblem::commit(double t_new, double dt) {
  const MacroState s = state(t_new, dt);
  for (auto& term : terms_) term->commit(s);
  x_nm1_ = x_n_;
  dt_n_ = dt;
  x_n_ = x_;
  v_n_ = v_;
  a_n_ = a_;
  t_n_ = t_new;
}

std::vector<std::pair<std::string, double>> MacroProblem::observe() const {
  const MacroState s = state(t_n_, dt_n_);
  std::vector<Observable> all;
  for (const auto& term : terms_) term->observe(s, all);
  // Sums in one reduction; a minimum as the maximum of its negative.
  std::vector<double> sums;
  for (const Observable& o : all) sums.push_back(o.minimum ? 0.0 : o.value);
  group_.allreduce_sum(sums.data(), static_cast<int>(sums.size()));
  std::vector<std::pair<std::string, double>> out;
  for (size_t k = 0; k < all.size(); ++k)
    out.emplace_back(all[k].name, all[k].minimum ? -group_.allreduce_max(-all[k].value) : sums[k]);
  return out;
}

void MacroProblem::rollback() {
  for (auto& term : terms_) term->rollback();
  x_ = x_n_;
  v_ = v_n_;
  a_ = a_n_;
}

void MacroProblem::save(ByteWriter& w) const {
  w.put(t_n_);
  w.put_array(x_n_.data(), static_cast<size_t>(x_n_.size()));
  w.put_array(v_n_.data(), static_cast<size_t>(v_n_.size()));
  w.put_array(a_n_.data(), static_cast<size_t>(a_n_.size()));
  w.put_array(x_nm1_.data(), static_cast<size_t>(x_nm1_.size()));
  w.put(dt_n_);
  w.put<uint64_t>(terms_.size());
  for (const auto& term : terms_) {
    w.put_string(term->name());
    term->save(w);
  }
}

void MacroProblem::restore(ByteReader& r) {
  t_n_ = r.get<double>();
  r.get_array_into(x_n_.data(), static_cast<size_t>(x_n_.size()));
  r.get_array_into(v_n_.data(), static_cast<size_t>(v_n_.size()));
  r.get_array_into(a_n_.data(), static_cast<size_t>(a_n_.size()));
  r.get_array_into(x_nm1_.data(), static_cast<size_t>(x_nm1_.size()));
  dt_n_ = r.get<double>();
  const auto terms = r.get<uint64_t>();
  if (terms != terms_.size())
    throw InputError(fmt::format("{}: {} macro terms where this run has {}", r.what(), terms, terms_.size()));
  for (auto& term : terms_) {
    const std::string name = r.get_string();
    if (name != term->name())
      throw InputError(fmt::format("{}: macro term '{}' where this run has '{}'", r.what(), name, term->name()));
    term->restore(r);
  }
  x_ = x_n_;
  v_ = v_n_;
  a_ = a_n_;
}

Eigen::SparseMatrix<double> MacroProblem::tangent() const {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(values_.size());
  for (size_t s = 0; s < values_.size(); ++s)
    entries.emplace_back(system_.rows()[s], system_.cols()[s], values_[s]);
  Eigen::SparseMatrix<double> K(system_.num_free(), system_.num_free());
  K.setFromTriplets(entries.begin(), entries.end());
  return K;
}

}  // namespace fe2
