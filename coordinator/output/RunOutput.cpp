#include "coordinator/output/RunOutput.h"

#include "common/mesh/cavity_volume.h"

#include "common/circulation/beat_report.h"
#include "common/circulation/circulation_report.h"
#include "common/io/atomic_file.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>

namespace fe2 {

namespace fs = std::filesystem;

bool is_run_output_file(const std::string& name) {
  // Keep in step with what RunOutput, Trace and tools/trace_plot.py write.
  static const std::regex own(
      "(summary\\.json|spec\\.json|fe2heart\\.log|displacement\\.pvd|displacement_[0-9]+\\.vtu|"
      "trace_[a-z_]+\\.jsonl|cumulative_times\\.png|gantt\\.png|gantt_all\\.png|imbalance\\.png|"
      "pv_curve\\.png|pv_loop\\.png|pv_time\\.png|circulation\\.csv|"
      "checkpoint\\.bin|checkpoint\\.bin\\.previous|checkpoint\\.bin\\.partial|"
      "units/unit_[0-9]+\\.pvd|units/unit_[0-9]+_[0-9]+\\.vtu)"
      "(\\.tmp)?");
  return std::regex_match(name, own);
}

std::vector<std::string> run_output_files(const std::string& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return names;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file(ec) && is_run_output_file(name)) names.push_back(name);
  }
  std::error_code absent;  // a missing units/ is no error
  if (!ec && fs::is_directory(fs::path(dir) / "units", absent))  // output.units (UnitOutput)
    for (const auto& e : fs::directory_iterator(fs::path(dir) / "units", ec)) {
      const std::string name = "units/" + e.path().filename().string();
      if (e.is_regular_file(ec) && is_run_output_file(name)) names.push_back(name);
    }
  if (ec)
    throw InputError(fmt::format("--out '{}': cannot list the output folder ({})", dir, ec.message()));
  std::sort(names.begin(), names.end());
  return names;
}

RunOutput::RunOutput(const std::string& dir, const RunSpec& spec, bool resume) : dir_(dir) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec || !fs::is_directory(dir_))
    throw InputError(fmt::format("--out '{}': cannot create the output folder ({})", dir_,
                                 ec.message()));
  // No stale VTU of steps this run never reaches may sit beside its own.
  for (const std::string& name : resume ? std::vector<std::string>{} : run_output_files(dir_)) {
    fs::remove(fs::path(dir_) / name, ec);
    if (ec)
      throw InputError(fmt::format("--out '{}': cannot remove '{}' of the earlier run ({})", dir_,
                                   name, ec.message()));
  }
  write_file_atomically(dir_ + "/spec.json", spec.raw.dump(2) + "\n");
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3 * spec.mesh.num_nodes());
  for (const auto& [name, surface] : spec.cavities)
    reference_volumes_.push_back(cavity_volume(spec.mesh, surface, zero).volume);
  if (spec.write_vtu) pvd_ = std::make_unique<PvdWriter>(pvd_path());
  if (resume) return;  // resume() rewrites the summary
  // Before the first step: the summary of a run killed during it says so.
  json s;
  s["title"] = spec.title;
  s["complete"] = false;
  s["converged"] = false;
  s["steps"] = 0;
  s["newton_iterations"] = 0;
  json probes = json::object();
  for (const auto& [name, X] : spec.probes) probes[name] = {X[0], X[1], X[2]};
  s["probes"] = probes;
  s["history"] = json::array();
  write_file_atomically(dir_ + "/summary.json", s.dump(2) + "\n");
}

void RunOutput::resume(const RunResult& done, const std::function<bool(int)>& is_output_step) {
  progress_ = done;
  if (!pvd_) return;
  auto relist = [&](int step, double time) {
    const std::string path = dir_ + "/" + fmt::format("displacement_{:05d}.vtu", step);
    if (fs::exists(path)) pvd_->add(time, path);
  };
  relist(0, 0.0);
  for (const StepRecord& r : done.history)
    if (is_output_step(r.step)) relist(r.step + 1, r.time);
}

std::string RunOutput::pvd_path() const { return dir_ + "/displacement.pvd"; }

void RunOutput::write_fields(const Simulation& sim, const PointFields& fields, int step,
                             double time) {
  const std::vector<Vec9>& P = fields.P;
  const TetMesh& mesh = sim.spec().mesh;
  const Eigen::VectorXd u = sim.displacement();
  std::vector<Vec3> disp(mesh.num_nodes());
  for (int a = 0; a < mesh.num_nodes(); ++a) disp[a] = u.segment<3>(3 * a);
  VtuFields point, cell;
  // The fluid: its velocity, pressure and mesh velocity; its nodes off the wall move
  // with the mesh displacement (so "Warp By Vector" moves wall and fluid alike).
  if (const Field* v = sim.system().fields().find("fluid_velocity")) {
    auto at_nodes = [&](const Field& f, const Eigen::VectorXd& x) {
      const Eigen::VectorXd all = f.at_every_node(x, mesh.num_nodes());
      std::vector<Vec3> out(mesh.num_nodes());
      for (int a = 0; a < mesh.num_nodes(); ++a) out[a] = all.segment<3>(3 * a);
      return out;
    };
    point.add_vector("fluid_velocity", at_nodes(*v, sim.state()));
    point.add_scalar("fluid_pressure", sim.vertex_field_at_nodes("fluid_pressure"));
    if (const Field* d = sim.system().fields().find("mesh_displacement")) {
      point.add_vector("mesh_velocity", at_nodes(*d, sim.rates()));
      const std::vector<Vec3> moved = at_nodes(*d, sim.state());
      for (int a : d->nodes())
        if (!sim.system().field("displacement").has_node(a)) disp[a] = moved[a];
    }
  }
  point.add_vector("displacement", disp);
  if (sim.system().fields().find("pressure")) point.add_scalar("pressure", sim.nodal_pressure());
  if (!pvd_) return;
  // Cell values are volume-weighted means over the element's integration points.
  const MacroPoints& points = sim.points();
  const int ne = mesh.num_tets();
  std::vector<double> detF(ne, 0.0), region(ne), model(ne), Ta(ne, 0.0);
  std::vector<Vec3> fibre(ne, Vec3::Zero());
  std::vector<Vec9> P_cell(ne, Vec9::Zero());
  for (int e = 0; e < ne; ++e) {
    double volume = 0.0;
    for (int k = points.first_point(e); k < points.first_point(e + 1); ++k) {
      const double w = points[k].volume;
      volume += w;
      detF[e] += w * (Mat3::Identity() + as_mat3(sim.displacement_gradient(k))).determinant();
      P_cell[e] += w * P[k];
      Ta[e] += w * fields.active_tension[k];
      fibre[e] += w * sim.frame(k).col(0);
    }
    region[e] = mesh.region[e];
    if (volume == 0.0) {  // off the wall: no points, no model (written as −1)
      model[e] = -1;
      continue;
    }
    detF[e] /= volume;
    P_cell[e] /= volume;
    Ta[e] /= volume;
    fibre[e].normalize();
    model[e] = sim.spec().model_index_of_tet(e);
  }
  cell.add_tensor("P_bar", P_cell);
  cell.add_scalar("det_F", detF);
  if (sim.spec().formulation.element_pressure) cell.add_scalar("pressure_element", sim.element_pressure());
  if (sim.spec().contracts()) cell.add_scalar("active_tension", Ta);
  cell.add_scalar("region", region);
  cell.add_scalar("model", model);
  cell.add_vector("fibre", fibre);
  // The path as written (relative to the working directory or absolute); the PVD
  // stores it relative to itself.
  const std::string path = dir_ + "/" + fmt::format("displacement_{:05d}.vtu", step);
  write_vtu(path, mesh, point, cell);
  pvd_->add(time, path);
}

void RunOutput::write_progress(const Simulation& sim, const StepRecord& step, double wall) {
  progress_.history.push_back(step);
  progress_.steps = step.step + 1;
  progress_.newton_iterations += step.iterations;
  write(sim, progress_, wall, false);
}

void RunOutput::write_summary(const Simulation& sim, const RunResult& r, double wall) {
  write(sim, r, wall, true);
}

namespace {

/// What the run is and how far it got; probes at the current state.
json run_status(const Simulation& sim, const RunResult& r, bool complete) {
  json s;
  s["title"] = sim.spec().title;
  s["complete"] = complete && !r.stopped;
  s["converged"] = complete && r.converged;
  if (r.stopped) s["stopped"] = "by a signal, after a checkpoint (continue with --restart)";
  s["steps"] = r.steps;
  s["newton_iterations"] = r.newton_iterations;
  if (!r.error.empty()) s["error"] = r.error;
  json probes = json::object();
  for (const auto& [name, X] : sim.spec().probes) {
    const Vec3 x = sim.deformed_position(X);
    probes[name] = {x[0], x[1], x[2]};
  }
  s["probes"] = probes;
  s["time"] = r.history.empty() ? 0.0 : r.history.back().time;
  return s;
}

/// Circulation-coupled cavities of one step: pressure, phase, valve flows; the compartments.
void add_step_circulation(const Circulation& c, const StepRecord& h, json& step) {
  const auto& names = c.cavity_names();
  json cav = json::object();
  const CavityFlows& f = h.circulation;
  for (size_t k = 0; k < names.size(); ++k) {
    json one = {{"pressure", h.cavity_pressures[k]}};
    if (f.n > 0)
      one.update({{"phase", f.phase[k]}, {"Q_in", f.Q_in[k]}, {"Q_out", f.Q_out[k]},
                  {"inflow_open", static_cast<bool>(f.inflow_open[k])},
                  {"outflow_open", static_cast<bool>(f.outflow_open[k])}});
    cav[names[k]] = one;
  }
  step["circulation"] = cav;
  if (f.n > 0) {
    json comp = json::object();
    const auto cn = c.compartment_names();
    for (size_t k = 0; k < cn.size() && k < f.pressures.size(); ++k) comp[cn[k]] = f.pressures[k];
    step["compartment_pressures"] = comp;
  }
}

/// One entry of summary.json's history.
json step_entry(const RunSpec& spec, const StepRecord& h) {
  // Each macro field's residual norm per Newton iteration, and the largest |Δx| of each
  // correction taken (in the field's units), under the field's name.
  json residuals = json::object(), corrections = json::object();
  for (const auto& f : h.residuals) {
    residuals[f.field] = f.values;
    corrections[f.field] = f.corrections;
  }
  json step = {{"step", h.step},
               {"time", h.time},
               {"iterations", h.iterations},
               {"cutbacks", h.cutbacks},
               {"retries", h.retries},
               {"residuals", residuals},
               {"corrections", corrections},
               {"micro_residuals", h.micro_residuals},
               {"gmres_iterations", h.gmres_iterations},
               {"refreshes", h.refreshes},
               {"forced_refreshes", h.forced_refreshes},
               {"collective_refreshes", h.collective_refreshes},
               {"wall_seconds", h.wall_seconds}};
  if (spec.line_search.backtracking) step["line_search_backtracks"] = h.line_search_backtracks;
  if (!h.cavity_volumes.empty()) {
    json cav = json::object();
    for (size_t c = 0; c < h.cavity_volumes.size(); ++c) cav[spec.cavities[c].first] = h.cavity_volumes[c];
    step["cavity_volumes"] = cav;
  }
  if (!h.load_pressures.empty()) step["load_pressures"] = h.load_pressures;
  if (!h.observables.empty()) {
    json o = json::object();
    for (const auto& [name, value] : h.observables) o[name] = value;
    step["observables"] = o;
  }
  if (!h.cavity_pressures.empty()) add_step_circulation(*spec.circulation, h, step);
  if (!h.probes.empty()) {
    json at = json::object();
    for (size_t p = 0; p < h.probes.size(); ++p)
      at[spec.probes[p].first] = {h.probes[p][0], h.probes[p][1], h.probes[p][2]};
    step["probes"] = at;
  }
  return step;
}

/// The sums over the steps that summary.json reports for the whole run.
struct RunTotals {
  int gmres = 0, refreshes = 0, forced_refreshes = 0, collective_refreshes = 0;
  double micro_cpu = 0.0;
  int evictions = 0, rebuilds = 0;
  double rebuild_cpu = 0.0;
};

RunTotals run_totals(const std::vector<StepRecord>& history) {
  RunTotals t;
  for (const auto& h : history) {
    t.gmres += h.gmres_iterations;
    t.refreshes += h.refreshes;
    t.forced_refreshes += h.forced_refreshes;
    t.collective_refreshes += h.collective_refreshes;
    t.micro_cpu += h.micro_cpu_seconds;
    t.evictions += h.factor_evictions;
    t.rebuilds += h.factor_rebuilds;
    t.rebuild_cpu += h.factor_rebuild_cpu_seconds;
  }
  return t;
}

/// Per cavity: its surface, the pressure loads on it (the pressure–volume curve of
/// history[*].load_pressures against history[*].cavity_volumes), reference and current volume.
json cavity_entries(const RunSpec& spec, const std::vector<double>& reference_volumes,
                    const std::vector<double>& now) {
  json cavities = json::object();
  for (size_t c = 0; c < spec.cavities.size(); ++c) {
    json loads = json::array();
    for (size_t p = 0; p < spec.pressure.size(); ++p)
      if (spec.pressure[p].surface == spec.cavities[c].second) loads.push_back(p);
    cavities[spec.cavities[c].first] = {{"surface", spec.cavities[c].second},
                                        {"pressure_loads", loads},
                                        {"reference_volume", reference_volumes[c]},
                                        {"volume", now[c]}};
  }
  return cavities;
}

/// The coupled cavities' samples as `fe2heart circulation` has them: the state at t = 0
/// (the undeformed wall at rest, or the end of the end-diastolic inflation), then one per
/// beat step up to a failed last step (which has no flows).
std::vector<CirculationSample> circulation_samples(const RunSpec& spec, const std::vector<StepRecord>& history,
                                                   const std::vector<double>& reference_volumes) {
  const Circulation& c = *spec.circulation;
  std::vector<CirculationSample> run(1);
  const size_t first = static_cast<size_t>(spec.inflation_steps);
  if (first > 0 && history.size() < first) return {};  // stopped while inflating: no beat yet
  if (first > 0) {
    run[0].p = history[first - 1].cavity_pressures;
    for (int k = 0; k < c.cavities(); ++k) run[0].V.push_back(history[first - 1].cavity_volumes[spec.coupled_cavities[k]]);
  } else {
    run[0].p.assign(c.cavities(), 0.0);
    for (int k = 0; k < c.cavities(); ++k) run[0].V.push_back(reference_volumes[spec.coupled_cavities[k]]);
  }
  for (size_t i = first; i < history.size(); ++i) {
    const StepRecord& h = history[i];
    if (h.circulation.n == 0) break;
    CirculationSample x;
    x.t = h.time;
    x.p = h.cavity_pressures;
    for (int k = 0; k < c.cavities(); ++k) x.V.push_back(h.cavity_volumes[spec.coupled_cavities[k]]);
    x.flows = h.circulation;
    x.blood_volume = 0.0;
    for (double v : h.circulation.volumes) x.blood_volume += v;
    for (double v : x.V) x.blood_volume += v;
    x.newton_iterations = h.circulation.newton_iterations;
    run.push_back(std::move(x));
  }
  return run;
}

/// The solver's and the farm's account of the run.
void add_solver_figures(const Simulation& sim, const RunTotals& t, json& s) {
  s["gmres_iterations"] = t.gmres;
  s["refreshes"] = t.refreshes;
  s["forced_refreshes"] = t.forced_refreshes;  // iterations all units refactored because Newton stalled
  s["collective_refreshes"] = t.collective_refreshes;  // refresh "collective": iterations × models refactored together
  s["micro_cpu_seconds"] = t.micro_cpu;
  // farm.factor_memory_budget: how often ranks dropped a unit's factor to stay within it,
  // and how often (and at what CPU cost) a dropped factor was rebuilt on a later job.
  const FarmOptions& farm = sim.spec().farm;
  s["factor_memory"] = {{"budget_bytes", farm.factor_memory_budget > 0 ? json(farm.factor_memory_budget) : json()},
                        {"evictions", t.evictions},
                        {"rebuilds", t.rebuilds},
                        {"rebuild_cpu_seconds", t.rebuild_cpu}};
}

/// The macro problem's size and solver.
void add_macro_figures(const Simulation& sim, json& s) {
  s["points"] = sim.points().size();
  s["elements"] = sim.spec().mesh.num_tets();
  s["element_order"] = sim.spec().mesh.order();
  s["formulation"] = sim.spec().formulation.mixed ? "mixed" : "displacement";
  s["macro_unknowns"] = sim.system().num_free();
  json by_field = json::object();  // DOFs per field (prescribed ones included)
  for (const Field& f : sim.system().fields()) by_field[f.name()] = f.size();
  s["macro_field_dofs"] = by_field;
  s["macro_ordering"] = sim.macro_ordering();
  const MacroSolver::Stats& ms = sim.macro_solver_stats();
  s["macro_solver"] = {{"refresh", sim.spec().macro_solver.refresh == MacroSolverOptions::Refresh::adaptive
                                       ? "adaptive"
                                       : "every_iteration"},
                       {"factorizations", ms.factorizations},
                       {"kept_factor_solves", ms.reused},
                       {"gmres_iterations", ms.gmres_iterations},
                       {"factor_entries", ms.factor_entries},
                       {"factor_flops", ms.factor_flops}};
}

}  // namespace

void RunOutput::write_circulation(const RunSpec& spec, const RunResult& r, bool complete, json& s) const {
  // circulation.csv is what `fe2heart circulation` writes, so tools/pv_loop_plot.py draws
  // pv_loop.png from either; the figures need a window of two steps.
  const std::vector<CirculationSample> run = circulation_samples(spec, r.history, reference_volumes_);
  if (run.size() >= 3) {
    s["circulation"] = beat_report(*spec.circulation, run);
    // Sample k is the beat's step k; steps count the inflation's too (output file numbers).
    s["circulation"]["systole_step"] = s["circulation"]["systole_step"].get<int>() + spec.inflation_steps;
    s["circulation"]["periodic"] = r.periodic;
    s["circulation"]["EDV_change_last_beat"] = r.edv_change;
  }
  if (complete && !run.empty()) write_file_atomically(dir_ + "/circulation.csv", circulation_csv(*spec.circulation, run));
}

void RunOutput::write(const Simulation& sim, const RunResult& r, double wall, bool complete) {
  const RunSpec& spec = sim.spec();
  json s = run_status(sim, r, complete);
  json hist = json::array();
  for (const auto& h : r.history) hist.push_back(step_entry(spec, h));
  s["history"] = hist;
  if (spec.circulation && r.history.size() >= 2) write_circulation(spec, r, complete, s);
  if (!spec.cavities.empty()) s["cavities"] = cavity_entries(spec, reference_volumes_, sim.cavity_volumes());
  add_solver_figures(sim, run_totals(r.history), s);
  s["wall_seconds"] = wall;
  add_macro_figures(sim, s);
  if (pvd_) s["fields"] = fs::path(pvd_path()).filename().string();
  write_file_atomically(dir_ + "/summary.json", s.dump(2) + "\n");
}

}  // namespace fe2
