#include "coordinator/RunOutput.h"

#include "common/io/atomic_file.h"

#include <filesystem>
#include <fstream>

namespace fe2 {

RunOutput::RunOutput(const std::string& dir, const RunSpec& spec) : dir_(dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec || !std::filesystem::is_directory(dir_))
    throw InputError(fmt::format("--out '{}': cannot create the output folder ({})", dir_,
                                 ec.message()));
  write_file_atomically(dir_ + "/spec.json", spec.raw.dump(2) + "\n");
  if (spec.write_vtu) pvd_ = std::make_unique<PvdWriter>(pvd_path());
}

std::string RunOutput::pvd_path() const { return dir_ + "/displacement.pvd"; }

void RunOutput::write_fields(const Simulation& sim, const std::vector<Vec9>& P, int step,
                             double time) {
  const TetMesh& mesh = sim.spec().mesh;
  const auto& u = sim.displacement();
  std::vector<Vec3> disp(mesh.num_nodes());
  for (int a = 0; a < mesh.num_nodes(); ++a) disp[a] = u.segment<3>(3 * a);
  VtuFields point, cell;
  point.add_vector("displacement", disp);
  if (!pvd_) return;
  std::vector<double> detF(mesh.num_tets()), region(mesh.num_tets()), model(mesh.num_tets());
  std::vector<Vec3> fibre(mesh.num_tets());
  for (int e = 0; e < mesh.num_tets(); ++e) {
    Eigen::Matrix<double, 12, 1> ue;
    for (int a = 0; a < 4; ++a) ue.segment<3>(3 * a) = u.segment<3>(3 * mesh.tets[e][a]);
    const Vec9 Z = sim.points()[e].B * ue;
    detF[e] = (Mat3::Identity() + as_mat3(Z)).determinant();
    region[e] = mesh.region[e];
    model[e] = sim.spec().model_index_of_tet(e);
    fibre[e] = sim.frame(e).col(0);
  }
  cell.add_tensor("P_bar", P);
  cell.add_scalar("det_F", detF);
  cell.add_scalar("region", region);
  cell.add_scalar("model", model);
  cell.add_vector("fibre", fibre);
  const std::string name = fmt::format("displacement_{:05d}.vtu", step);
  write_vtu(dir_ + "/" + name, mesh, point, cell);
  pvd_->add(time, name);
}

void RunOutput::write_summary(const Simulation& sim, const RunResult& r, double wall) {
  json s;
  s["title"] = sim.spec().title;
  s["converged"] = r.converged;
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
  int gmres = 0, refreshes = 0;
  double micro_cpu = 0.0;
  for (const auto& h : r.history) {
    hist.push_back({{"step", h.step},
                    {"time", h.time},
                    {"iterations", h.iterations},
                    {"cutbacks", h.cutbacks},
                    {"residuals", h.residuals},
                    {"micro_residuals", h.micro_residuals},
                    {"gmres_iterations", h.gmres_iterations},
                    {"refreshes", h.refreshes},
                    {"wall_seconds", h.wall_seconds}});
    gmres += h.gmres_iterations;
    refreshes += h.refreshes;
    micro_cpu += h.micro_cpu_seconds;
  }
  s["history"] = hist;
  s["gmres_iterations"] = gmres;
  s["refreshes"] = refreshes;
  s["micro_cpu_seconds"] = micro_cpu;
  s["wall_seconds"] = wall;
  s["points"] = sim.spec().mesh.num_tets();
  if (pvd_) s["fields"] = std::filesystem::path(pvd_path()).filename().string();
  write_file_atomically(dir_ + "/summary.json", s.dump(2) + "\n");
}

}  // namespace fe2
