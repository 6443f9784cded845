#include "coordinator/output/RunOutput.h"

#include "common/mesh/cavity_volume.h"

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

void check_output_folder(const std::string& dir, bool overwrite) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw InputError(fmt::format("--out '{}' exists and is not a folder; expected a folder for the "
                                 "run's output (new, empty, or an earlier run with --overwrite)",
                                 dir));
  const std::vector<std::string> earlier = run_output_files(dir);
  if (earlier.empty() || overwrite) return;
  const std::size_t shown = std::min<std::size_t>(earlier.size(), 4);
  throw InputError(fmt::format(
      "--out '{}' already holds an fe2heart run ({} file{}: {}{}); use --overwrite to replace "
      "it, or another --out",
      dir, earlier.size(), earlier.size() == 1 ? "" : "s", fmt::join(earlier.begin(), earlier.begin() + shown, ", "),
      earlier.size() > shown ? ", ..." : ""));
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
    detF[e] /= volume;
    P_cell[e] /= volume;
    Ta[e] /= volume;
    fibre[e].normalize();
    region[e] = mesh.region[e];
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

void RunOutput::write(const Simulation& sim, const RunResult& r, double wall, bool complete) {
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
  json hist = json::array();
  int gmres = 0, refreshes = 0, forced_refreshes = 0, collective_refreshes = 0;
  double micro_cpu = 0.0;
  int evictions = 0, rebuilds = 0;
  double rebuild_cpu = 0.0;
  for (const auto& h : r.history) {
    // Each macro field's residual norm per Newton iteration, under the field's name.
    json residuals = json::object();
    for (const auto& f : h.residuals) residuals[f.field] = f.values;
    hist.push_back({{"step", h.step},
                    {"time", h.time},
                    {"iterations", h.iterations},
                    {"cutbacks", h.cutbacks},
                    {"residuals", residuals},
                    {"micro_residuals", h.micro_residuals},
                    {"gmres_iterations", h.gmres_iterations},
                    {"refreshes", h.refreshes},
                    {"forced_refreshes", h.forced_refreshes},
                    {"collective_refreshes", h.collective_refreshes},
                    {"wall_seconds", h.wall_seconds}});
    if (!h.cavity_volumes.empty()) {
      json cav = json::object();
      for (size_t c = 0; c < h.cavity_volumes.size(); ++c) cav[sim.spec().cavities[c].first] = h.cavity_volumes[c];
      hist.back()["cavity_volumes"] = cav;
    }
    if (!h.load_pressures.empty()) hist.back()["load_pressures"] = h.load_pressures;
    if (!h.cavity_pressures.empty()) {
      // Circulation-coupled cavities: pressure, phase, valve flows; the compartments.
      const auto& names = sim.spec().circulation->cavity_names();
      json cav = json::object();
      const CavityFlows& f = h.circulation;
      for (size_t c = 0; c < names.size(); ++c) {
        json one = {{"pressure", h.cavity_pressures[c]}};
        if (f.n > 0)
          one.update({{"phase", f.phase[c]}, {"Q_in", f.Q_in[c]}, {"Q_out", f.Q_out[c]},
                      {"inflow_open", static_cast<bool>(f.inflow_open[c])},
                      {"outflow_open", static_cast<bool>(f.outflow_open[c])}});
        cav[names[c]] = one;
      }
      hist.back()["circulation"] = cav;
      if (f.n > 0) {
        json comp = json::object();
        const auto cn = sim.spec().circulation->compartment_names();
        for (size_t k = 0; k < cn.size() && k < f.pressures.size(); ++k) comp[cn[k]] = f.pressures[k];
        hist.back()["compartment_pressures"] = comp;
      }
    }
    if (!h.probes.empty()) {
      json at = json::object();
      for (size_t p = 0; p < h.probes.size(); ++p)
        at[sim.spec().probes[p].first] = {h.probes[p][0], h.probes[p][1], h.probes[p][2]};
      hist.back()["probes"] = at;
    }
    gmres += h.gmres_iterations;
    refreshes += h.refreshes;
    forced_refreshes += h.forced_refreshes;
    collective_refreshes += h.collective_refreshes;
    micro_cpu += h.micro_cpu_seconds;
    evictions += h.factor_evictions;
    rebuilds += h.factor_rebuilds;
    rebuild_cpu += h.factor_rebuild_cpu_seconds;
  }
  s["history"] = hist;
  // Per cavity: its surface, the pressure loads on it (the pressure–volume curve of
  // history[*].load_pressures against history[*].cavity_volumes), reference and current volume.
  json cavities = json::object();
  const auto& spec = sim.spec();
  const std::vector<double> now = sim.cavity_volumes();
  for (size_t c = 0; c < spec.cavities.size(); ++c) {
    json loads = json::array();
    for (size_t p = 0; p < spec.pressure.size(); ++p)
      if (spec.pressure[p].surface == spec.cavities[c].second) loads.push_back(p);
    cavities[spec.cavities[c].first] = {{"surface", spec.cavities[c].second},
                                        {"pressure_loads", loads},
                                        {"reference_volume", reference_volumes_[c]},
                                        {"volume", now[c]}};
  }
  if (spec.circulation && r.history.size() >= 2) {  // figures need a window of two steps
    // The beat through the circulation's eyes: circulation.csv (as `fe2heart circulation`
    // writes it, so tools/pv_loop_plot.py draws pv_loop.png) and the figures of the last
    // period (or of the whole run, if shorter).
    const Circulation& c = *spec.circulation;
    std::vector<CirculationSample> run(1);
    run[0].p.assign(c.cavities(), 0.0);
    for (int k = 0; k < c.cavities(); ++k) run[0].V.push_back(reference_volumes_[spec.coupled_cavities[k]]);
    for (const auto& h : r.history) {
      if (h.circulation.n == 0) break;  // a failed last step
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
    if (run.size() >= 3) {  // a window of at least two steps
      const double period = c.period(), t_end = run.back().t;
      // The window: the last period, or the whole run without its unloaded initial state.
      size_t first = 1;
      while (first + 1 < run.size() && run[first + 1].t <= t_end - period + 1e-9 * period) ++first;
      const int per_beat = static_cast<int>(std::lround(period / (t_end / static_cast<double>(run.size() - 1))));
      const int beats = per_beat > 0 ? static_cast<int>((run.size() - 1) / static_cast<size_t>(per_beat)) : 0;
      s["circulation"] = {{"description", c.description()},
                          {"beats_run", beats},
                          {"periodic", r.periodic},
                          {"EDV_change_last_beat", r.edv_change},
                          {"figures_over", t_end >= period * (1 - 1e-9) ? "the last period" : "the whole run (shorter than a period)"},
                          {"period", period},
                          {"cavities", cavity_figures(c, run, first, run.size() - 1, beats, per_beat)}};
      // Systole: the step of peak LV pressure in the window ("lv", else the first cavity),
      // numbered as displacement_<step>.vtu and units/unit_<id>_<step>.vtu are.
      const auto& names = c.cavity_names();
      const size_t lv = std::find(names.begin(), names.end(), "lv") != names.end()
                            ? static_cast<size_t>(std::find(names.begin(), names.end(), "lv") - names.begin())
                            : 0;
      size_t systole = first;
      for (size_t i = first; i < run.size(); ++i)
        if (run[i].p[lv] > run[systole].p[lv]) systole = i;
      s["circulation"]["systole_step"] = systole;
      s["circulation"]["systole_time"] = run[systole].t;
      s["circulation"]["systole_cavity"] = names[lv];
    }
    if (complete) write_file_atomically(dir_ + "/circulation.csv", circulation_csv(c, run));
  }
  if (!spec.cavities.empty()) s["cavities"] = cavities;
  s["gmres_iterations"] = gmres;
  s["refreshes"] = refreshes;
  s["forced_refreshes"] = forced_refreshes;  // iterations all units refactored because Newton stalled
  s["collective_refreshes"] = collective_refreshes;  // refresh "collective": iterations × models refactored together
  s["micro_cpu_seconds"] = micro_cpu;
  // farm.factor_memory_budget: how often ranks dropped a unit's factor to stay within it,
  // and how often (and at what CPU cost) a dropped factor was rebuilt on a later job.
  const FarmOptions& farm = sim.spec().farm;
  s["factor_memory"] = {{"budget_bytes", farm.factor_memory_budget > 0 ? json(farm.factor_memory_budget) : json()},
                        {"evictions", evictions},
                        {"rebuilds", rebuilds},
                        {"rebuild_cpu_seconds", rebuild_cpu}};
  s["wall_seconds"] = wall;
  s["points"] = sim.points().size();
  s["elements"] = sim.spec().mesh.num_tets();
  s["element_order"] = sim.spec().mesh.order();
  s["formulation"] = sim.spec().formulation.mixed ? "mixed" : "displacement";
  s["macro_unknowns"] = sim.system().num_free();
  s["macro_ordering"] = sim.macro_ordering();
  const MacroSolver::Stats& ms = sim.macro_solver_stats();
  s["macro_solver"] = {{"refresh", sim.spec().macro_solver.refresh == MacroSolverOptions::Refresh::adaptive
                                       ? "adaptive"
                                       : "every_iteration"},
                       {"factorizations", ms.factorizations},
                       {"kept_factor_solves", ms.reused},
                       {"gmres_iterations", ms.gmres_iterations}};
  if (pvd_) s["fields"] = fs::path(pvd_path()).filename().string();
  write_file_atomically(dir_ + "/summary.json", s.dump(2) + "\n");
}

}  // namespace fe2
