#include "common/cpu_timer.h"
#include "coordinator/RunOutput.h"
#include "coordinator/RunSpec.h"
#include "coordinator/Simulation.h"
#include "tools/commands.h"
#include "tools/unit_spec.h"

#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

namespace fe2::cli {

namespace {
std::string describe(const RunSpec& spec) {
  int units = 0, dofs = 0;
  for (int e = 0; e < spec.mesh.num_tets(); ++e) {
    const auto& m = spec.models[spec.model_index_of_tet(e)];
    if (m.kind == PointModelSpec::Kind::fe2) ++units, dofs += m.micro->num_dofs();
  }
  return fmt::format("{} nodes, {} tetrahedra ({} FE² units, {} micro DOF in all), {} steps{}",
                     spec.mesh.num_nodes(), spec.mesh.num_tets(), units, dofs, spec.steps,
                     spec.dynamic ? ", Newmark dynamics" : ", quasi-static");
}
}  // namespace

int validate(const std::string& file) {
  const json j = read_json_file(file);
  if (j.is_object() && j.contains("unit") && !j.contains("mesh")) {
    const UnitSpec u = read_unit_spec(j, file);
    fmt::print("{}: OK: unit spec, {} hexahedra, {} DOF, {} macro gradient(s)\n", file,
               u.model->num_elements(), u.model->num_dofs(), u.path.size());
    return 0;
  }
  const RunSpec spec = read_run_spec(j, file);
  fmt::print("{}: OK: {}\n", file, describe(spec));
  return 0;
}

int run(const RunOptions& o) {
  int ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (ranks != 1)
    throw InputError(fmt::format("fe2heart run: launched on {} ranks, expected 1: this build "
                                 "runs every point on one process (mpirun -np 1)", ranks));
  const RunSpec spec = read_run_spec_file(o.spec);
  RunOutput output(o.out, spec);
  auto file_sink = std::make_shared<spdlog::sinks::basic_file_sink_mt>(o.out + "/fe2heart.log", true);
  spdlog::default_logger()->sinks().push_back(file_sink);
  spdlog::info("fe2heart run {}: {}", o.spec, spec.title);
  spdlog::info("{}", describe(spec));

  LocalEvaluator points(spec.models, spec.model_of_points());
  Simulation sim(spec, points, MPI_COMM_WORLD);
  const double t0 = wall_seconds();
  output.write_fields(sim, 0, 0.0);
  const RunResult result = sim.run([&](const StepRecord& r) {
    spdlog::info("step {:4d}  t = {:<10.5g} Newton {:2d}  |R|/F = {:.2e}  max |r|/r_ref = {:.2e}"
                 "  GMRES {:5d}  refreshes {:4d}{}  {:.2f} s",
                 r.step + 1, r.time, r.iterations, r.residuals.back(), r.micro_residuals.back(),
                 r.gmres_iterations, r.refreshes,
                 r.cutbacks ? fmt::format("  cutbacks {}", r.cutbacks) : "", r.wall_seconds);
    if ((r.step + 1) % spec.output_every == 0 || r.step + 1 == spec.steps)
      output.write_fields(sim, r.step + 1, r.time);
  });
  output.write_summary(sim, result, wall_seconds() - t0);
  if (!result.converged) {
    spdlog::error("run stopped: {}", result.error);
    spdlog::info("partial results in {}", o.out);
    return 3;
  }
  spdlog::info("done in {:.2f} s: {} steps, {} Newton iterations", wall_seconds() - t0,
               result.steps, result.newton_iterations);
  spdlog::info("results: {}/summary.json{}", o.out,
               spec.write_vtu ? fmt::format(", fields: {} (open in ParaView)", output.pvd_path()) : "");
  return 0;
}

}  // namespace fe2::cli
