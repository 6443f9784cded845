#include "coordinator/Simulation.h"

#include "coordinator/failure_diagnosis.h"
#include "coordinator/macro/CavityPressureTerm.h"
#include "coordinator/macro/gather.h"

#include "common/cpu_timer.h"
#include "common/fem/lagrange_tet.h"
#include "common/mesh/cavity_volume.h"
#include "common/mesh/point_locator.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace fe2 {

namespace {

/// A Newton iteration whose convergence measure is above this fraction of the previous
/// one's has stopped contracting (a kept-factor Newton contracts by 0.1–0.5 per iteration).
constexpr double kStallRatio = 0.9;

}  // namespace

const std::vector<double>& StepRecord::residual(const std::string& field) const {
  static const std::vector<double> none;
  for (const auto& r : residuals)
    if (r.field == field) return r.values;
  return none;
}

const std::vector<double>& StepRecord::correction(const std::string& field) const {
  static const std::vector<double> none;
  for (const auto& r : residuals)
    if (r.field == field) return r.corrections;
  return none;
}

Simulation::Simulation(const RunSpec& spec, PointEvaluator& points, const MacroExtension& extension)
    : Simulation(spec, points, proto::Group(), MacroPartition::whole(spec.mesh), extension) {}

Simulation::Simulation(const RunSpec& spec, PointEvaluator& points, const proto::Group& coordinators,
                       MacroPartition partition, const MacroExtension& extension)
    : spec_(spec),
      self_(coordinators.valid() ? MPI_COMM_NULL : MPI_COMM_SELF),
      group_(coordinators.valid() ? coordinators : self_),
      partition_(std::move(partition)),
      problem_(spec, group_, make_macro_system(spec, extension)),
      displacement_field_(problem_.system().field("displacement")),
      coupling_(spec, points, group_, partition_.elements(), displacement_field_),
      stepper_(spec.load_steps, spec.dt()) {
  FE2_CHECK(partition_.part() == group_.rank() && partition_.parts() == group_.size(),
            "coordinator {} of {} given part {} of {}", group_.rank(), group_.size(), partition_.part(),
            partition_.parts());
  if (problem_.system().num_free() == 0)
    throw InputError("the Dirichlet conditions fix every degree of freedom: nothing to solve");
  if (const MacroExtension scene = scene_extension(spec, extension); scene.initial) problem_.set_initial(scene.initial);
  // The scene's terms (macro/macro_scene.h); an effect that is off builds nothing.
  for (auto& term : scene_terms(spec, coupling_.points(), partition_, coupling_.responses())) {
    if (auto* cavities = dynamic_cast<CavityPressureTerm*>(term.get())) cavity_term_ = cavities;
    problem_.add_term(std::move(term));
  }
}

void Simulation::add_term(std::unique_ptr<MacroTerm> term) { problem_.add_term(std::move(term)); }

// --- observables of the current state

Vec9 Simulation::displacement_gradient(int point) const {
  const MacroPoint& p = coupling_.points()[point];
  return p.B * gather(state(), displacement_field_.node_dofs(spec_.mesh.element_nodes(p.element)));
}

Vec3 Simulation::deformed_position(const Vec3& X) const {
  const MeshPoint p = locate_point(spec_.mesh, X);
  Eigen::VectorXd N;
  Eigen::Matrix<double, 3, Eigen::Dynamic> dN;
  tet_shape(spec_.mesh.order(), Vec4(p.bary[0], p.bary[1], p.bary[2], p.bary[3]), N, dN);
  const std::vector<int> nodes = spec_.mesh.element_nodes(p.tet);
  Vec3 x = X;
  for (size_t a = 0; a < nodes.size(); ++a) x += N[a] * state().segment<3>(displacement_field_.node_dof(nodes[a]));
  return x;
}

std::vector<double> Simulation::cavity_volumes() const {
  std::vector<double> v;
  const Eigen::VectorXd u = displacement();
  for (const auto& [name, surface] : spec_.cavities) v.push_back(cavity_volume(spec_.mesh, surface, u).volume);
  return v;
}

std::vector<double> Simulation::nodal_pressure() const { return vertex_field_at_nodes("pressure"); }

std::vector<double> Simulation::vertex_field_at_nodes(const std::string& name) const {
  const Field* field = system().fields().find(name);
  if (!field) return {};
  const TetMesh& m = spec_.mesh;
  std::vector<double> p(m.num_nodes(), 0.0);
  for (int a : field->nodes()) p[a] = state()[field->node_dof(a)];
  for (const auto& [edge, node] : m.edge_nodes)
    if (field->has_node(edge.first) && field->has_node(edge.second)) p[node] = 0.5 * (p[edge.first] + p[edge.second]);
  return p;
}

std::vector<double> Simulation::element_pressure() const {
  std::vector<double> p(spec_.mesh.num_tets(), 0.0);
  const Field* field = system().fields().find("pressure");
  if (!field) return p;
  for (int e = 0; e < spec_.mesh.num_tets(); ++e)
    if (field->element_dof(e) >= 0) p[e] = state()[field->element_dof(e)];
  return p;
}

void Simulation::observe(StepRecord& rec) const {
  const double t = problem_.committed_time();
  rec.time = t;
  rec.cavity_volumes = cavity_volumes();
  for (const auto& probe : spec_.probes) rec.probes.push_back(deformed_position(probe.second));
  if (cavity_term_) {
    const Field& pc = system().field("cavity_pressure");
    for (int c = 0; c < pc.size(); ++c) rec.cavity_pressures.push_back(state()[pc.global_dof(c)]);
    rec.circulation = cavity_term_->flows();  // valid on the coordinator that assembles it
  }
  for (const auto& ps : spec_.pressure) rec.load_pressures.push_back(ps.value * ramp_factor(ps.ramp, t, spec_.t_end));
  rec.observables = problem_.observe();
}

// --- (i): convergence, the same on every coordinator

Simulation::Residual Simulation::converge(double t_new) {
  Residual res;
  for (const auto& r : coupling_.results()) res.micro = std::max(res.micro, proto::relative_residual(r));
  res.micro = group_.allreduce_max(res.micro);
  res.fields = problem_.residual_norms(t_new);
  return res;
}

std::string Simulation::describe(const Residual& r) const {
  std::string text;
  for (const Field& f : system().fields()) text += fmt::format("{} {:.3e}, ", f.name(), r.fields[f.id()]);
  return text + fmt::format("micro {:.3e}", r.micro);
}

double Simulation::convergence_measure(const Residual& r) const {
  double measure = r.micro / spec_.micro_rtol;
  for (const Field& f : system().fields()) measure = std::max(measure, r.fields[f.id()] / f.decl().rtol);
  return measure;
}

void Simulation::account_work(StepRecord& rec) const {
  // farm.factor_memory_budget: factors dropped, rebuilt, and the CPU seconds of those rebuilds.
  enum Counter { gmres, refreshes, cpu, evictions, rebuilds, rebuild_cpu, kCounters };
  std::array<double, kCounters> work{};
  for (const auto& r : coupling_.results()) {
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

// Kept factors make the coupled Newton linear (stale χ in Eq. (11) and A_hom in Eq. (7));
// far from the factored state it can stop contracting, or diverge (micro contrast 1e3, a
// large step). Then every unit refactors in the next iteration, which restores the exact
// Newton of Fig. 5; once in a row at most, so a Newton that diverges with fresh factors
// still ends in a cut-back. All coordinators hold the same (allreduced) residuals, so
// they decide alike.
bool Simulation::StallGuard::stalled(int it, double measure, bool converged, bool refreshed) {
  const bool stall = !converged && !refreshed && it >= 3 && measure > kStallRatio * previous;
  previous = measure;
  return stall;
}

// --- one Newton iteration (paper Fig. 5)

Simulation::Outcome Simulation::iterate(int step, int it, double t_new, double dt, const Eigen::VectorXd* lift,
                                        StepRecord& rec, StallGuard& stall, IterationTiming& timing,
                                        LineSearch* search) {
  ScopedWallTimer entire(timing.entire);
  problem_.predict(dt);
  {
    // c = ∂Ż̄/∂Z̄: the displacement's scheme (Newmark: γ/(βΔt)); without a field rate the
    // points' rates are backward differences of Z̄. Their tangents take ∂Π/∂Ż with this weight.
    ScopedWallTimer t(timing.micro_lc);
    const bool field_rate = displacement_field_.decl().time != TimeScheme::none;
    const double c = field_rate ? problem_.state(t_new, dt).rate(displacement_field_).dv_dx : 1.0 / dt;
    coupling_.evaluate(step, it, t_new, dt, problem_.x(), problem_.v(), field_rate, c);
  }
  ScopedWallTimer macro(timing.macro);
  ScopedCpuTimer macro_cpu(timing.macro_cpu_max);  // this rank's; newton() takes the group's max
  {
    ScopedWallTimer t(timing.assemble);
    problem_.assemble(t_new, dt, lift);
  }
  timing.assemble_fluid = problem_.fluid_assembly_seconds();
  const Residual res = converge(t_new);
  for (size_t f = 0; f < res.fields.size(); ++f) rec.residuals[f].values.push_back(res.fields[f]);
  rec.micro_residuals.push_back(res.micro);
  account_work(rec);
  spdlog::debug("step {} t={:.6g} it {}: {}", step, t_new, it, describe(res));
  const double measure = convergence_measure(res);
  const bool converged = !lift && measure <= 1.0;
  const bool refreshed = coupling_.refresh_forced();
  coupling_.force_refresh(false);
  CollectiveRefresh& collective = coupling_.collective();
  if (collective.active()) {
    rec.collective_refreshes += refreshed ? 0 : collective.due_models();
    collective.account(coupling_.results(), refreshed, [&](int64_t* v, int n) { group_.allreduce_sum(v, n); });
  }
  const double before = stall.previous;
  if (stall.stalled(it, measure, converged, refreshed)) {
    coupling_.force_refresh(true);
    ++rec.forced_refreshes;
    spdlog::info("step {} t={:.6g} iteration {}: the coupled residual did not contract ({:.3e} -> {:.3e} of "
                 "its tolerance); every unit refactors in the next iteration",
                 step, t_new, it, before, measure);
  }
  if (converged) return Outcome::converged;
  if (search && search->judge(measure) == LineSearch::Verdict::retry) {
    spdlog::debug("step {} t={:.6g} it {}: line search rejects the trial (merit {:.3e}); next α = {:.3g}", step,
                  t_new, it, measure, search->alpha());
    return Outcome::rejected;
  }
  {
    ScopedWallTimer t(timing.solve);
    const MacroSolver::Stats before = macro_solver_stats();
    problem_.solve(it == 1 && !spec_.dynamic);
    timing.macro_factorized = macro_solver_stats().factorizations - before.factorizations;
    timing.macro_gmres = macro_solver_stats().gmres_iterations - before.gmres_iterations;
  }
  if (search) search->start(measure);
  return Outcome::solved;
}

namespace {

/// Appends a correction's per-field norms to the step's histories (table order).
void record_corrections(StepRecord& rec, const std::vector<double>& norms) {
  for (size_t f = 0; f < norms.size() && f < rec.residuals.size(); ++f) rec.residuals[f].corrections.push_back(norms[f]);
}

}  // namespace

bool Simulation::newton(int step, double t_new, double dt, StepRecord& rec) {
  problem_.prepare();
  const Eigen::VectorXd du_D = problem_.prescribed_increment(t_new);
  const bool has_du_D = du_D.squaredNorm() > 0.0;
  rec.residuals.clear();
  for (const Field& f : system().fields()) rec.residuals.push_back({f.name(), {}, {}});
  rec.micro_residuals.clear();
  coupling_.force_refresh(false);
  StallGuard stall;
  LineSearch search(spec_.line_search);
  bool lifted = false;  // the correction being tried carries Δx_D
  for (int it = 1; it <= spec_.newton_max_iterations; ++it) {
    if (stop_poll_ && stop_poll_()) throw StopRequested{};
    IterationTiming timing;
    timing.step = step;
    timing.iteration = it;
    const bool first = it == 1 && has_du_D;
    Outcome outcome;
    try {
      outcome = iterate(step, it, t_new, dt, first ? &du_D : nullptr, rec, stall, timing,
                        search.active() ? &search : nullptr);
    } catch (const SingularMatrixError&) {
      throw;  // the solve failed: no correction is left to shorten
    } catch (const NumericalError& e) {
      // A trial of the line search that inverts an element (or is non-finite) is a step
      // too long, not yet a failed step: shorten it, down to line_search_min_step.
      if (!search.active() || it == 1 || search.judge(std::numeric_limits<double>::infinity()) ==
                                              LineSearch::Verdict::give_up)
        throw;
      spdlog::debug("step {} t={:.6g} it {}: line search: {}; next α = {:.3g}", step, t_new, it, e.what(),
                    search.alpha());
      outcome = Outcome::rejected;
    }
    // Every coordinator gets here alike (the outcomes are agreed): the group's macro CPU.
    timing.coordinators = group_.size();
    timing.macro_cpu_sum = timing.macro_cpu_max;
    group_.allreduce_sum(&timing.macro_cpu_sum, 1);
    timing.macro_cpu_max = group_.allreduce_max(timing.macro_cpu_max);
    if (on_iteration_) on_iteration_(timing);
    if (outcome == Outcome::converged) {
      rec.iterations += it;
      rec.line_search_backtracks += search.backtracks();
      return true;
    }
    if (outcome == Outcome::rejected) {
      problem_.retract(search.alpha(), lifted, du_D);
      record_corrections(rec, problem_.correction_norms(search.alpha()));
      continue;
    }
    lifted = first;
    try {
      problem_.update(first, du_D);
    } catch (const NumericalError& e) {
      throw NumericalError(fmt::format("{} at t = {:.6g}", e.what(), t_new));
    }
    record_corrections(rec, problem_.correction_norms());
  }
  rec.iterations += spec_.newton_max_iterations;
  rec.line_search_backtracks += search.backtracks();
  return false;
}

void Simulation::commit(double t_new, double dt) {
  coupling_.commit();
  problem_.commit(t_new, dt);
}

void Simulation::rollback() {
  coupling_.rollback();
  problem_.rollback();
}

// --- time stepping

std::string Simulation::advance(int step, double t_target, StepRecord& rec) {
  stepper_.begin_step();
  InversionRecord inversions;
  // Solves of one step again with a discrete choice a term changed (MacroTerm::accept);
  // past this many the choice stands (a valve that would chatter).
  constexpr int kMaxRetries = 3;
  int retries = 0;
  while (problem_.committed_time() < t_target - 1e-12 * spec_.t_end) {
    const double t_n = problem_.committed_time();
    double t_new = stepper_.next_time(t_n, t_target);
    // The inflation ends, and the beat starts, at t = 0 exactly (not at a rounding of it).
    if (t_target == 0.0 && -t_new < 1e-12 * spec_.t_end) t_new = 0.0;
    std::string why;
    const int iterations_before = rec.iterations;
    try {
      if (newton(step, t_new, t_new - t_n, rec)) {
        if (!problem_.accept(t_new, t_new - t_n) && retries < kMaxRetries) {
          ++retries;
          ++rec.retries;
          spdlog::info("step {} t={:.6g}: the converged state contradicts a valve's state; solving the step again "
                       "with it changed", step, t_new);
          rollback();
          continue;
        }
        retries = 0;
        // The units' fields of an output step, from the converged state before it
        // becomes the committed one (worker/unit_fields.h).
        if (!spec_.output_units.empty() && is_output_step(step) && t_new >= t_target - 1e-12 * spec_.t_end)
          unit_fields_ = coupling_.unit_fields(spec_.output_units, step + 1);
        commit(t_new, t_new - t_n);
        stepper_.converged(rec.iterations - iterations_before);
        continue;
      }
      std::string last;
      for (const auto& r : rec.residuals) last += fmt::format("{} {:.3e}, ", r.field, r.values.back());
      why = fmt::format("Newton did not converge in {} iterations (last residuals: {}max unit |r|/r_ref {:.3e})",
                        spec_.newton_max_iterations, last, rec.micro_residuals.back());
    } catch (const SingularMatrixError& e) {
      if (e.at_committed_state) {
        rollback();
        return fmt::format("step {} (t = {:.6g} → {:.6g}): {}", step, t_n, t_new, e.what());
      }
      why = e.what();
    } catch (const NumericalError& e) {
      why = e.what();
    } catch (const StopRequested&) {
      rollback();
      stopped_in_step_ = true;
      return "";
    }
    rollback();
    // An element that inverts again and again as the step shrinks: say whether it is the mesh.
    const std::string diagnosis = inversions.record(spec_.mesh, why);
    if (!stepper_.failed())
      return fmt::format("step {} (t = {:.6g} → {:.6g}) failed {}: {}{}{}", step, t_n, t_new,
                         stepper_.give_up_reason(), why, diagnosis, volume_diagnosis());
    ++rec.cutbacks;
    spdlog::warn("step {}: {}; cutting the step to dt = {:.4g}", step, why, stepper_.dt());
  }
  return "";
}

std::string Simulation::volume_diagnosis() const {
  if (!spec_.formulation.mixed) return "";
  // J̄_e of the committed state, the volume-weighted mean of det F̄ over each element's points.
  std::vector<double> J(spec_.mesh.num_tets(), 0.0), volume(spec_.mesh.num_tets(), 0.0);
  for (int k = 0; k < points().size(); ++k) {
    const MacroPoint& p = points()[k];
    J[p.element] += p.volume * (Mat3::Identity() + as_mat3(displacement_gradient(k))).determinant();
    volume[p.element] += p.volume;
  }
  for (size_t e = 0; e < J.size(); ++e) J[e] = volume[e] > 0.0 ? J[e] / volume[e] : -1.0;
  return fe2::volume_diagnosis(spec_.mesh, J, !spec_.formulation.element_pressure);
}

bool Simulation::beat_is_periodic(RunResult& result) const {
  // At the end of beat b ≥ 2: the largest relative change of a cavity's EDV (its largest
  // volume over the beat) from beat b − 1. The same on every coordinator (x is).
  // The beat's steps follow the inflation's.
  const int per = spec_.steps_per_beat, first = spec_.inflation_steps;
  const int n = static_cast<int>(result.history.size()) - first;
  if (spec_.beats == 0 || per == 0 || n <= 0 || n % per != 0 || n < 2 * per) return false;
  double change = 0.0;
  const auto& h = result.history;
  for (size_t c = 0; c < spec_.cavities.size(); ++c) {
    double last = 0.0, before = 0.0;
    for (int s = first + n - per; s < first + n; ++s) last = std::max(last, h[s].cavity_volumes[c]);
    for (int s = first + n - 2 * per; s < first + n - per; ++s) before = std::max(before, h[s].cavity_volumes[c]);
    change = std::max(change, std::abs(last - before) / last);
  }
  result.edv_change = change;
  return spec_.periodic_tolerance > 0.0 && change < spec_.periodic_tolerance;
}

bool Simulation::is_output_step(int step) const {
  return (step + 1) % spec_.output_every == 0 || step + 1 == spec_.steps;
}

RunResult Simulation::run(const StepHook& on_step, const IterationHook& on_iteration, RunResult done) {
  on_iteration_ = on_iteration;
  RunResult result = std::move(done);
  result.converged = false;
  for (int step = result.steps; step < spec_.steps; ++step) {
    StepRecord rec;
    rec.step = step;
    const double t0 = wall_seconds();
    const double t_target = spec_.step_end_time(step);
    result.error = advance(step, t_target, rec);
    if (stopped_in_step_) {  // a stop request inside the step: the committed state stands
      result.stopped = true;
      result.converged = true;
      return result;
    }
    if (!result.error.empty()) {
      result.history.push_back(rec);
      return result;
    }
    observe(rec);
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
                   (step + 1 - spec_.inflation_steps) / spec_.steps_per_beat, result.edv_change,
                   spec_.periodic_tolerance);
      result.periodic = true;
      break;
    }
  }
  result.converged = true;
  return result;
}

// --- checkpoints

void Simulation::save_state(ByteWriter& w) {
  problem_.save(w);
  coupling_.collective().save(w);
  problem_.drop_factor();
}

void Simulation::restore_state(ByteReader& r) {
  problem_.restore(r);
  coupling_.collective().restore(r);
  coupling_.restore(problem_.x());
  problem_.drop_factor();
}

}  // namespace fe2
