#include "coordinator/Simulation.h"

#include "coordinator/macro/CavityPressureTerm.h"
#include "coordinator/macro/field_residuals.h"
#include "coordinator/macro/gather.h"

#include "common/cpu_timer.h"
#include "common/fem/lagrange_tet.h"
#include "common/mesh/cavity_volume.h"
#include "common/mesh/point_locator.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace fe2 {

namespace {

/// A Newton iteration whose convergence measure is above this fraction of the previous
/// one's has stopped contracting (a kept-factor Newton contracts by 0.1–0.5 per iteration).
constexpr double kStallRatio = 0.9;

std::vector<int> all_elements(const TetMesh& m) {
  std::vector<int> v(m.num_tets());
  for (int e = 0; e < m.num_tets(); ++e) v[e] = e;
  return v;
}

/// Per point model: whether its units refresh collectively (unit.solver.refresh).
std::vector<bool> collective_models(const RunSpec& spec) {
  std::vector<bool> c;
  for (const auto& m : spec.models)
    c.push_back(m.kind == PointModelSpec::Kind::fe2 && m.plan &&
                m.plan->options.refresh == MicroSolverOptions::Refresh::collective);
  return c;
}

}  // namespace

Simulation::Simulation(const RunSpec& spec, PointEvaluator& points, const MacroExtension& extension)
    : Simulation(spec, points, proto::Group(), all_elements(spec.mesh), extension) {}

Simulation::Simulation(const RunSpec& spec, PointEvaluator& points, const proto::Group& coordinators,
                       std::vector<int> owned_elements, const MacroExtension& extension)
    : spec_(spec),
      evaluator_(points),
      self_(coordinators.valid() ? MPI_COMM_NULL : MPI_COMM_SELF),
      group_(coordinators.valid() ? coordinators : self_),
      owned_elements_(std::move(owned_elements)),
      points_(spec.mesh, spec.formulation.quadrature_degree),
      owned_points_(points_.points_of(owned_elements_)),
      system_(make_macro_system(spec, extension)),
      time_integration_(spec.beta, spec.gamma),
      macro_solver_(group_, system_.num_free(), spec.macro_solver),
      displacement_field_(system_.field("displacement")),
      collective_(spec.model_of_points(), collective_models(spec)) {
  FE2_CHECK(points_.points_per_element() == spec.points_per_element,
            "{} points per element, the spec counted {}", points_.points_per_element(),
            spec.points_per_element);
  if (system_.num_free() == 0)
    throw InputError("the Dirichlet conditions fix every degree of freedom: nothing to solve");
  // The material frame at every point (a rule-based field solves its Laplace problems here).
  const auto field = spec.frame.built ? spec.frame.built : make_frame_field(spec.frame.field, spec.mesh);
  const int np = points_.size();
  Q_.resize(np);
  R_.resize(np);
  activation_time_.assign(np, 0.0);
  for (int k = 0; k < np; ++k) {
    const Vec4& l = points_[k].bary;
    const Bary bary{l[0], l[1], l[2], l[3]};
    Q_[k] = field->at(points_[k].element, bary, points_[k].X);
    R_[k] = frame_rotation(Q_[k]);
    if (spec.activation) activation_time_[k] = spec.activation->at(points_[k].element, bary);
  }
  for (int k : owned_points_)
    point_dofs_.push_back(displacement_field_.node_dofs(spec.mesh.element_nodes(points_[k].element)));

  // The scene's terms (macro/macro_scene.h); an effect that is off builds nothing.
  responses_.resize(owned_points_.size());
  terms_ = scene_terms(spec, points_, owned_elements_, responses_, group_.rank(), group_.size());
  for (const auto& term : terms_)
    if (auto* cavities = dynamic_cast<CavityPressureTerm*>(term.get())) cavity_term_ = cavities;

  const int n = system_.num_dofs();
  x_ = v_ = a_ = Eigen::VectorXd::Zero(n);
  system_.constraints().distribute(x_);  // ties with an offset hold from the start
  x_n_ = x_;
  v_n_ = v_;
  a_n_ = a_;
  Zbar_.assign(owned_points_.size(), Vec9::Zero());
  Zbar_n_ = Zbar_;
  jobs_.resize(owned_points_.size());
  dirichlet_value_ = [this](int k, double t) { return system_.prescribed_value(k, t); };
}

void Simulation::add_term(std::unique_ptr<MacroTerm> term) {
  FE2_CHECK(!pattern_set_, "macro term '{}' added after the first solve", term->name());
  terms_.push_back(std::move(term));
}

Vec9 Simulation::displacement_gradient(int point) const {
  const MacroPoint& p = points_[point];
  return p.B * gather(x_, displacement_field_.node_dofs(spec_.mesh.element_nodes(p.element)));
}

Eigen::VectorXd Simulation::field_values(const std::string& name) const {
  const Field& f = system_.field(name);
  return x_.segment(f.offset(), f.size());
}

const std::vector<double>& StepRecord::residual(const std::string& field) const {
  static const std::vector<double> none;
  for (const auto& r : residuals)
    if (r.field == field) return r.values;
  return none;
}

Vec3 Simulation::deformed_position(const Vec3& X) const {
  const MeshPoint p = locate_point(spec_.mesh, X);
  Eigen::VectorXd N;
  Eigen::Matrix<double, 3, Eigen::Dynamic> dN;
  tet_shape(spec_.mesh.order(), Vec4(p.bary[0], p.bary[1], p.bary[2], p.bary[3]), N, dN);
  const std::vector<int> nodes = spec_.mesh.element_nodes(p.tet);
  Vec3 x = X;
  for (size_t a = 0; a < nodes.size(); ++a) x += N[a] * x_.segment<3>(displacement_field_.node_dof(nodes[a]));
  return x;
}

std::vector<double> Simulation::cavity_volumes() const {
  std::vector<double> v;
  const Eigen::VectorXd u = displacement();
  for (const auto& [name, surface] : spec_.cavities) v.push_back(cavity_volume(spec_.mesh, surface, u).volume);
  return v;
}

std::vector<double> Simulation::nodal_pressure() const {
  const Field* field = system_.fields().find("pressure");
  if (!field) return {};
  const TetMesh& m = spec_.mesh;
  std::vector<double> p(m.num_nodes(), 0.0);
  for (int a : field->nodes()) p[a] = x_[field->node_dof(a)];
  for (const auto& [edge, node] : m.edge_nodes) p[node] = 0.5 * (p[edge.first] + p[edge.second]);
  return p;
}

std::vector<double> Simulation::element_pressure() const {
  std::vector<double> p(spec_.mesh.num_tets(), 0.0);
  const Field* field = system_.fields().find("pressure");
  if (!field) return p;
  for (int e = 0; e < spec_.mesh.num_tets(); ++e)
    if (field->element_dof(e) >= 0) p[e] = x_[field->element_dof(e)];
  return p;
}

void Simulation::agree_on_failure(const std::string& why) const {
  const int failed = group_.allreduce_max(static_cast<int>(!why.empty()));
  if (!failed) return;
  // The lowest failing coordinator's reason, for every coordinator.
  const int first = -group_.allreduce_max(why.empty() ? -group_.size() : -group_.rank());
  Bytes text;
  if (group_.rank() == first) text.assign(reinterpret_cast<const std::byte*>(why.data()),
                                          reinterpret_cast<const std::byte*>(why.data()) + why.size());
  group_.bcast(text, first);
  throw NumericalError(std::string(reinterpret_cast<const char*>(text.data()), text.size()));
}

PointFields Simulation::gather_point_fields() const {
  // P̄ (9) and T_a (1) per point, summed onto the first coordinator.
  constexpr size_t kPer = 10;
  std::vector<double> flat(kPer * static_cast<size_t>(points_.size()), 0.0);
  for (size_t s = 0; s < owned_points_.size(); ++s) {
    double* at = &flat[kPer * static_cast<size_t>(owned_points_[s])];
    std::copy(responses_[s].P_bar.data(), responses_[s].P_bar.data() + 9, at);
    at[9] = responses_[s].active_tension;
  }
  group_.reduce_sum(flat.data(), static_cast<int>(flat.size()), 0);
  PointFields f;
  f.P.resize(points_.size());
  f.active_tension.resize(points_.size());
  for (int k = 0; k < points_.size(); ++k) {
    f.P[k] = Eigen::Map<const Vec9>(&flat[kPer * static_cast<size_t>(k)]);
    f.active_tension[k] = flat[kPer * static_cast<size_t>(k) + 9];
  }
  return f;
}

MacroState Simulation::state(double t_new, double dt) const {
  MacroState s{x_, v_, a_, t_new, dt, {}};
  for (const Field& f : system_.fields()) s.rates.push_back(time_integration_.coefficients(f, dt));
  return s;
}

Eigen::VectorXd Simulation::dirichlet_increment(double t_new) const {
  Eigen::VectorXd du_D = Eigen::VectorXd::Zero(system_.num_dofs());
  const auto& prescribed = system_.prescribed();
  for (size_t k = 0; k < prescribed.size(); ++k)
    du_D[prescribed[k]] = dirichlet_value_(static_cast<int>(k), t_new) - x_n_[prescribed[k]];
  return du_D;
}

// --- predict: each field's rates of the trial x, by its scheme
void Simulation::predict(double dt) {
  for (const Field& f : system_.fields()) time_integration_.rates(f, dt, x_, x_n_, v_n_, a_n_, v_, a_);
}

// --- (a)–(e): the points answer, agreed valid on every coordinator
void Simulation::evaluate_points(int step, int iteration, double t_new, double dt) {
  // c = ∂Ż̄/∂Z̄: the displacement's scheme (Newmark: γ/(βΔt)); without a field rate the
  // points' rates are backward differences of Z̄. Their tangents take ∂Π/∂Ż with this weight.
  const bool u_has_rate = displacement_field_.decl().time != TimeScheme::none;
  const double Zdot_coefficient = u_has_rate ? time_integration_.coefficients(displacement_field_, dt).dv_dx : 1.0 / dt;
  std::string why;
  try {
    for (size_t s = 0; s < owned_points_.size(); ++s) {
      const int k = owned_points_[s];
      const MacroPoint& p = points_[k];
      const Vec9 Zbar = p.B * gather(x_, point_dofs_[s]);
      const Vec9 Zdot = u_has_rate ? Vec9(p.B * gather(v_, point_dofs_[s])) : Vec9((Zbar - Zbar_n_[s]) / dt);
      // Non-finite first: NaN compares false, so it would pass as "inverted" below.
      if (!Zbar.allFinite() || !Zdot.allFinite())
        throw NumericalError(fmt::format("non-finite macro displacement gradient Z̄ or rate Ż̄ at "
                                         "point {} (element {}), t = {:.6g}, dt = {:.3g}",
                                         k, p.element, t_new, dt));
      const double J = (Mat3::Identity() + as_mat3(Zbar)).determinant();
      if (!std::isfinite(J))
        throw NumericalError(fmt::format("non-finite det F̄ at point {} (element {}), t = {:.6g}", k,
                                         p.element, t_new));
      if (!(J > 0.0))
        throw NumericalError(fmt::format("macro element {} inverted at point {}, t = {:.6g} (det F̄ = {:.3e})",
                                         p.element, k, t_new, J));
      Zbar_[s] = Zbar;
      proto::JobInput& job = jobs_[s];
      job.unit = k;
      job.step = step;
      job.iteration = iteration;
      job.time = t_new;
      job.dt = dt;
      job.apply_update = iteration > 1;
      job.force_refresh = force_refresh_ || collective_.due(k) ? 1 : 0;
      job.Zbar = R_[k] * Zbar;  // Z̄_μ = QᵀZ̄Q
      job.Zbar_dot = R_[k] * Zdot;
      job.Zbar_dot_coefficient = Zdot_coefficient;
      job.activation_time = activation_time_[k];
    }
  } catch (const NumericalError& e) {
    why = e.what();
  }
  agree_on_failure(why);
  evaluator_.evaluate(jobs_, results_);
  for (const auto& r : results_) {
    if (!why.empty()) break;
    if (r.failed) why = r.message;
    else if (!r.A_hom.allFinite() || !r.P_tilde.allFinite() || !r.P_bar.allFinite() ||
             !std::isfinite(r.r_norm) || !std::isfinite(r.r_ref))
      why = fmt::format("point {}: non-finite stress, tangent or residual at t = {:.6g}", r.unit, t_new);
  }
  agree_on_failure(why);
  for (size_t s = 0; s < owned_points_.size(); ++s) {
    const Mat9& R = R_[owned_points_[s]];
    responses_[s].A = R.transpose() * results_[s].A_hom * R;  // back to the global frame
    responses_[s].P_tilde = R.transpose() * results_[s].P_tilde;
    responses_[s].P_bar = R.transpose() * results_[s].P_bar;
    responses_[s].active_tension = results_[s].active_tension;
  }
}

// --- (g): every term into S̄ and the residual
void Simulation::assemble(double t_new, double dt, const Eigen::VectorXd* lift) {
  assembly_->clear();
  assembly_->set_lift(lift);
  const MacroState s = state(t_new, dt);
  std::string why;
  try {
    for (auto& term : terms_) term->assemble(s, *assembly_);
  } catch (const NumericalError& e) {
    why = e.what();
  }
  agree_on_failure(why);
  assembly_->set_lift(nullptr);
}

// --- (i): the true residual per field, and the units' (identical on every coordinator)
Simulation::Residual Simulation::converge(double t_new) {
  Eigen::VectorXd& f_int = assembly_->internal();
  Eigen::VectorXd& f_ext = assembly_->external();
  group_.allreduce_sum(f_int.data(), static_cast<int>(f_int.size()));
  group_.allreduce_sum(f_ext.data(), static_cast<int>(f_ext.size()));
  Residual res;
  for (const auto& r : results_) res.micro = std::max(res.micro, proto::relative_residual(r));
  res.micro = group_.allreduce_max(res.micro);
  res.fields = field_residual_norms(system_, f_int, f_ext, residual_scales_);
  for (double v : res.fields)
    if (!std::isfinite(v)) throw NumericalError(fmt::format("non-finite macro residual at t = {:.6g} ({})", t_new, describe(res)));
  return res;
}

std::string Simulation::describe(const Residual& r) const {
  std::string text;
  for (const Field& f : system_.fields()) text += fmt::format("{} {:.3e}, ", f.name(), r.fields[f.id()]);
  return text + fmt::format("micro {:.3e}", r.micro);
}

double Simulation::convergence_measure(const Residual& r) const {
  double measure = r.micro / spec_.micro_rtol;
  for (const Field& f : system_.fields()) measure = std::max(measure, r.fields[f.id()] / f.decl().rtol);
  return measure;
}

// --- (h): S̄ Δx = −R̃ on the coordinators (summed on the MUMPS host), Δx to all
void Simulation::solve(int iteration) {
  du_ = assembly_->rhs();
  group_.reduce_sum(du_.data(), system_.num_free(), 0);
  try {
    macro_solver_.solve(values_, du_);
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
    if (iteration == 1 && !spec_.dynamic)
      throw SingularMatrixError(why + "; it is the matrix of the last converged state, so cutting "
                                "the step back cannot help",
                                true);
    throw SingularMatrixError(why, e.at_committed_state);
  }
  group_.bcast(du_.data(), system_.num_free(), 0);
}

// --- (j): x += Δx (and the prescribed increment after the first iteration)
void Simulation::update(bool first, const Eigen::VectorXd& du_D) {
  if (!std::all_of(du_.begin(), du_.end(), [](double x) { return std::isfinite(x); }))
    throw NumericalError("non-finite macro correction Δx");
  for (int dof = 0; dof < system_.num_dofs(); ++dof)
    if (system_.column(dof) >= 0) x_[dof] += du_[system_.column(dof)];
  if (first) x_ += du_D;
  system_.constraints().distribute(x_);  // tied and following DOFs exactly at their master's value
}

bool Simulation::newton(int step, double t_new, double dt, StepRecord& rec) {
  if (!pattern_set_) {
    for (auto& term : terms_) term->declare(system_);
    values_.assign(system_.rows().size(), 0.0);
    macro_solver_.set_pattern(system_.rows(), system_.cols());
    assembly_ = std::make_unique<MacroAssembly>(system_, values_);
    for (const Field& f : system_.fields()) {
      Eigen::VectorXd scale;
      if (f.decl().norm != ResidualNorm::relative_to_load) {
        scale = Eigen::VectorXd::Zero(f.size());
        for (const auto& term : terms_) term->add_residual_scale(f, scale);
        group_.allreduce_sum(scale.data(), static_cast<int>(scale.size()));
      }
      residual_scales_.push_back(std::move(scale));
    }
    pattern_set_ = true;
  }
  const Eigen::VectorXd du_D = dirichlet_increment(t_new);
  const bool has_du_D = du_D.squaredNorm() > 0.0;
  rec.residuals.clear();
  for (const Field& f : system_.fields()) rec.residuals.push_back({f.name(), {}});
  rec.micro_residuals.clear();
  force_refresh_ = false;
  double previous_measure = std::numeric_limits<double>::infinity();
  for (int it = 1; it <= spec_.newton_max_iterations; ++it) {
    IterationTiming timing;
    timing.step = step;
    timing.iteration = it;
    const bool first = it == 1 && has_du_D;
    bool converged = false;
    {
      ScopedWallTimer entire(timing.entire);
      predict(dt);
      {
        ScopedWallTimer t(timing.micro_lc);
        evaluate_points(step, it, t_new, dt);
      }
      ScopedWallTimer macro(timing.macro);
      {
        ScopedWallTimer t(timing.assemble);
        assemble(t_new, dt, first ? &du_D : nullptr);
      }
      const Residual res = converge(t_new);
      for (size_t f = 0; f < res.fields.size(); ++f) rec.residuals[f].values.push_back(res.fields[f]);
      rec.micro_residuals.push_back(res.micro);
      account_work(rec);
      spdlog::debug("step {} t={:.6g} it {}: {}", step, t_new, it, describe(res));
      const double measure = convergence_measure(res);
      converged = !first && measure <= 1.0;
      // Kept factors make the coupled Newton linear (stale χ in Eq. (11) and A_hom in
      // Eq. (7)); far from the factored state it can stop contracting, or diverge (micro
      // contrast 1e3, a large step). Then every unit refactors in the next iteration, which
      // restores the exact Newton of Fig. 5; once in a row at most, so a Newton that diverges
      // with fresh factors still ends in a cut-back. All coordinators hold the same
      // (allreduced) residuals, so they decide alike.
      const bool forced_now = force_refresh_;
      force_refresh_ = false;
      if (collective_.active()) {
        rec.collective_refreshes += forced_now ? 0 : collective_.due_models();
        collective_.account(results_, forced_now, [&](int64_t* v, int n) { group_.allreduce_sum(v, n); });
      }
      if (!converged && !forced_now && it >= 3 && measure > kStallRatio * previous_measure) {
        force_refresh_ = true;
        ++rec.forced_refreshes;
        spdlog::info("step {} t={:.6g} iteration {}: the coupled residual did not contract ({:.3e} -> {:.3e} of "
                     "its tolerance); every unit refactors in the next iteration",
                     step, t_new, it, previous_measure, measure);
      }
      previous_measure = measure;
      if (!converged) {
        ScopedWallTimer t(timing.solve);
        solve(it);
      }
    }
    if (on_iteration_) on_iteration_(timing);
    if (converged) {
      rec.iterations += it;
      return true;
    }
    try {
      update(first, du_D);
    } catch (const NumericalError& e) {
      throw NumericalError(fmt::format("{} at t = {:.6g}", e.what(), t_new));
    }
  }
  rec.iterations += spec_.newton_max_iterations;
  return false;
}

void Simulation::account_work(StepRecord& rec) const {
  // farm.factor_memory_budget: factors dropped, rebuilt, and the CPU seconds of those rebuilds.
  enum Counter { gmres, refreshes, cpu, evictions, rebuilds, rebuild_cpu, kCounters };
  std::array<double, kCounters> work{};
  for (const auto& r : results_) {
    work[gmres] += r.gmres_iterations;
    work[refreshes] += r.kind == proto::Refresh::refresh;
    work[cpu] += r.cpu_seconds;
    work[evictions] += r.factor_evictions;
    work[rebuilds] += r.factor_rebuilt;
    if (r.factor_rebuilt) work[rebuild_cpu] += r.cpu_refresh;
  }
  group_.allreduce_sum(work.data(), kCounters);
  rec.gmres_iterations += static_cast<int>(work[gmres]);
  rec.refreshes += static_cast<int>(work[refreshes]);
  rec.micro_cpu_seconds += work[cpu];
  rec.factor_evictions += static_cast<int>(work[evictions]);
  rec.factor_rebuilds += static_cast<int>(work[rebuilds]);
  rec.factor_rebuild_cpu_seconds += work[rebuild_cpu];
}

void Simulation::commit(double t_new, double dt) {
  evaluator_.commit_step();
  collective_.commit();
  const MacroState s = state(t_new, dt);
  for (auto& term : terms_) term->commit(s);
  Zbar_n_ = Zbar_;
  x_n_ = x_;
  v_n_ = v_;
  a_n_ = a_;
  t_n_ = t_new;
}

void Simulation::rollback() {
  evaluator_.rollback_step();
  collective_.rollback();
  for (auto& term : terms_) term->rollback();
  Zbar_ = Zbar_n_;
  x_ = x_n_;
  v_ = v_n_;
  a_ = a_n_;
}

bool Simulation::beat_is_periodic(RunResult& result) const {
  // At the end of beat b ≥ 2: the largest relative change of a cavity's EDV (its largest
  // volume over the beat) from beat b − 1. The same on every coordinator (x is).
  const int per = spec_.steps_per_beat, n = static_cast<int>(result.history.size());
  if (spec_.beats == 0 || per == 0 || n % per != 0 || n < 2 * per) return false;
  double change = 0.0;
  for (size_t c = 0; c < spec_.cavities.size(); ++c) {
    double last = 0.0, before = 0.0;
    for (int s = n - per; s < n; ++s) last = std::max(last, result.history[s].cavity_volumes[c]);
    for (int s = n - 2 * per; s < n - per; ++s) before = std::max(before, result.history[s].cavity_volumes[c]);
    change = std::max(change, std::abs(last - before) / last);
  }
  result.edv_change = change;
  return spec_.periodic_tolerance > 0.0 && change < spec_.periodic_tolerance;
}

bool Simulation::is_output_step(int step) const {
  return (step + 1) % spec_.output_every == 0 || step + 1 == spec_.steps;
}

void Simulation::save_state(ByteWriter& w) {
  w.put(t_n_);
  w.put_array(x_n_.data(), static_cast<size_t>(x_n_.size()));
  w.put_array(v_n_.data(), static_cast<size_t>(v_n_.size()));
  w.put_array(a_n_.data(), static_cast<size_t>(a_n_.size()));
  w.put<uint64_t>(terms_.size());
  for (const auto& term : terms_) {
    w.put_string(term->name());
    term->save(w);
  }
  collective_.save(w);
  macro_solver_.drop_factor();
}

void Simulation::restore_state(ByteReader& r) {
  t_n_ = r.get<double>();
  r.get_array_into(x_n_.data(), static_cast<size_t>(x_n_.size()));
  r.get_array_into(v_n_.data(), static_cast<size_t>(v_n_.size()));
  r.get_array_into(a_n_.data(), static_cast<size_t>(a_n_.size()));
  const auto terms = r.get<uint64_t>();
  if (terms != terms_.size())
    throw InputError(fmt::format("{}: {} macro terms where this run has {}", r.what(), terms, terms_.size()));
  for (auto& term : terms_) {
    const std::string name = r.get_string();
    if (name != term->name())
      throw InputError(fmt::format("{}: macro term '{}' where this run has '{}'", r.what(), name, term->name()));
    term->restore(r);
  }
  collective_.restore(r);
  x_ = x_n_;
  v_ = v_n_;
  a_ = a_n_;
  // Z̄_n as the last converged iteration computed it: B̄ ū_n.
  for (size_t s = 0; s < owned_points_.size(); ++s)
    Zbar_n_[s] = points_[owned_points_[s]].B * gather(x_n_, point_dofs_[s]);
  Zbar_ = Zbar_n_;
  macro_solver_.drop_factor();
}

RunResult Simulation::run(const StepHook& on_step, const IterationHook& on_iteration, RunResult done) {
  on_iteration_ = on_iteration;
  RunResult result = std::move(done);
  result.converged = false;
  const double dt_nominal = spec_.t_end / spec_.steps;
  for (int step = result.steps; step < spec_.steps; ++step) {
    StepRecord rec;
    rec.step = step;
    const double t0 = wall_seconds();
    const double t_target = (step + 1 == spec_.steps) ? spec_.t_end : (step + 1) * dt_nominal;
    int cut = 0;
    while (t_n_ < t_target - 1e-12 * spec_.t_end) {
      const double h = dt_nominal / std::ldexp(1.0, cut);
      const double t_new = std::min(t_n_ + h, t_target);
      std::string why;
      bool ok = false;
      try {
        ok = newton(step, t_new, t_new - t_n_, rec);
        if (!ok) {
          std::string last;
          for (const auto& r : rec.residuals) last += fmt::format("{} {:.3e}, ", r.field, r.values.back());
          why = fmt::format("Newton did not converge in {} iterations (last residuals: {}max unit |r|/r_ref "
                            "{:.3e})",
                            spec_.newton_max_iterations, last, rec.micro_residuals.back());
        }
      } catch (const SingularMatrixError& e) {
        if (e.at_committed_state) {
          rollback();
          result.error = fmt::format("step {} (t = {:.6g} → {:.6g}): {}", step, t_n_, t_new, e.what());
          result.history.push_back(rec);
          return result;
        }
        why = e.what();
      } catch (const NumericalError& e) {
        why = e.what();
      }
      if (ok) {
        // The units' fields of an output step, from the converged state before it
        // becomes the committed one (worker/unit_fields.h).
        if (!spec_.output_units.empty() && is_output_step(step) &&
            t_new >= t_target - 1e-12 * spec_.t_end)
          unit_fields_ = evaluator_.unit_fields(spec_.output_units, step + 1);
        commit(t_new, t_new - t_n_);
        continue;
      }
      rollback();
      if (++cut > spec_.max_cutbacks) {
        result.error = fmt::format("step {} (t = {:.6g} → {:.6g}) failed after {} cutbacks: {}",
                                   step, t_n_, t_new, spec_.max_cutbacks, why);
        result.history.push_back(rec);
        return result;
      }
      ++rec.cutbacks;
      spdlog::warn("step {}: {}; cutting the step to dt = {:.4g}", step, why,
                   dt_nominal / std::ldexp(1.0, cut));
    }
    rec.time = t_n_;
    rec.cavity_volumes = cavity_volumes();
    for (const auto& probe : spec_.probes) rec.probes.push_back(deformed_position(probe.second));
    if (cavity_term_) {
      const Field& pc = system_.field("cavity_pressure");
      for (int c = 0; c < pc.size(); ++c) rec.cavity_pressures.push_back(x_[pc.global_dof(c)]);
      rec.circulation = cavity_term_->flows();  // valid on the coordinator that assembles it
    }
    for (const auto& ps : spec_.pressure) rec.load_pressures.push_back(ps.value * ramp_factor(ps.ramp, t_n_, spec_.t_end));
    rec.wall_seconds = wall_seconds() - t0;
    result.newton_iterations += rec.iterations;
    result.steps = step + 1;
    result.history.push_back(rec);
    if (on_step) on_step(rec);
    // A stop requested in the last step finds the run complete: nothing is left to continue.
    if (stop_requested_ && step + 1 < spec_.steps) {
      result.stopped = true;
      break;
    }
    if (beat_is_periodic(result)) {
      spdlog::info("periodic after {} beats: EDV changed by {:.2e} (relative) over the last beat, "
                   "below time.periodic_tolerance = {:.1e}",
                   (step + 1) / spec_.steps_per_beat, result.edv_change, spec_.periodic_tolerance);
      result.periodic = true;
      break;
    }
  }
  result.converged = true;
  return result;
}

}  // namespace fe2
