// `fe2heart bench unit`: figures for one micro unit on one core (not a test).
// Prints medians over --repeat runs of: assembly into the fixed pattern; one Newton
// iteration with the cached factor (assembly, Step 1 GMRES, Eqs. 7 and 9) when K is
// the factored matrix, and when Z̄ has moved on by --stale-stretch and ten times that;
// a refresh (numeric factorization plus the 9 characteristic-mode solves); and
// CHOLMOD's own numeric factorization of the same matrix for comparison; and a
// unit's whole Newton solve on fresh factors, iteration by iteration. With
// --single, the same figures for a second unit whose factor is single precision
// (--single-factor: the supernodal float LLᵀ or MUMPS, with --blr-tolerance block
// low-rank), under "single".
#include "common/cpu_timer.h"
#include "common/error.h"
#include "common/median.h"
#include "common/materials/NeoHookean.h"
#include "tools/commands.h"
#include "worker/MicroUnit.h"
#include "worker/blas_core.h"
#include "worker/micro_cell.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace fe2::cli {

namespace {
// The runs' default micro_rtol: the bench's Newton solve stops where a run's would.
constexpr double kNewtonRtol = 1e-8;

double median(std::vector<double> v) { return fe2::median(std::move(v), std::numeric_limits<double>::quiet_NaN()); }
}  // namespace

int bench_blas(bool suggested_only) {
  const BlasCore core = blas_core();
  if (suggested_only) {
    fmt::print("{}\n", core.suggested);
    return 0;
  }
  const char* set = std::getenv("OPENBLAS_CORETYPE");
  const json j = {{"openblas_core", core.name},
                  {"cpu", core.cpu},
                  {"OPENBLAS_CORETYPE", set ? set : "unset"},
                  {"suggested_OPENBLAS_CORETYPE", core.suggested}};
  fmt::print("{}\n", j.dump(2));
  return 0;
}

int bench_unit(const BenchOptions& o) {
  const BlasCore core = blas_core();
  // On stderr: stdout is the JSON document.
  if (const std::string w = blas_core_warning(core); !w.empty()) fmt::print(stderr, "warning: {}\n", w);
  const int n = std::max(2, static_cast<int>(std::lround(std::cbrt(o.dofs / 3.0))));
  CellLayout layout;
  layout.kind = o.cell;
  layout.size = Vec3(1.0, 1.0, 1.0);
  layout.resolution = {n, n, n};
  std::vector<MaterialPtr> mats = {std::make_shared<NeoHookean>(1.0e4, 0.45)};
  if (o.cell != "homogeneous") mats.push_back(std::make_shared<NeoHookean>(1.0e5, 0.45));
  MicroSolverOptions opt;
  opt.refresh = MicroSolverOptions::Refresh::fixed;
  opt.N_t = 1 << 30;  // refreshes only when the benchmark asks
  opt.factorization = MicroSolverOptions::Factorization::cholesky;
  opt.newton_rtol = kNewtonRtol;
  opt.gmres_forcing = o.gmres_forcing == "constant" ? MicroSolverOptions::Forcing::constant
                                                    : MicroSolverOptions::Forcing::residual;
  Vec9 Z0 = Vec9::Zero();
  Z0[0] = 0.05;  // 5 % fibre stretch

  // Figures of one unit with these options; `cholmod` (when given) is refactored each
  // repeat for comparison.
  auto measure = [&](const MicroSolverOptions& uo, SparseFactor* cholmod_in,
                     double* cholmod_ms) {
    auto model = std::make_shared<const MicroModel>(make_cell_mesh(layout), mats, uo, "bench");
    MicroUnit unit(model);
    proto::JobInput job;
    job.step = 1;       // not a refresh step of the fixed policy: refreshes only when forced
    job.iteration = 2;
    job.Zbar = Z0;
    job.force_refresh = 1;
    const double t_first = thread_cpu_seconds();
    unit.iterate(job);  // symbolic analysis + first factorization
    const double first_ms = 1e3 * (thread_cpu_seconds() - t_first);

    std::vector<double> assembly, iteration, iteration_solve, refresh, factorize, gmres_its,
        iteration_stale, gmres_stale, iteration_staler, gmres_staler;
    MicroUnit::System sys;
    sys.K = model->zero_matrix();
    SparseFactor* cholmod = cholmod_in;
    if (cholmod) cholmod->factorize(unit.system().K);  // its own analysis, excluded from the timing
    for (int r = 0; r < o.repeat; ++r) {
      double t = thread_cpu_seconds();
      unit.assemble_at(unit.w(), Z0, sys);
      assembly.push_back(1e3 * (thread_cpu_seconds() - t));

      job.Zbar = Z0;
      job.force_refresh = 1;
      job.apply_update = 0;
      refresh.push_back(1e3 * unit.iterate(job).cpu_refresh);

      // A Newton iteration whose K is the factored one: the floor (1 GMRES iteration
      // with a double factor).
      job.force_refresh = 0;
      const proto::JobOutput fresh = unit.iterate(job);
      iteration.push_back(1e3 * fresh.cpu_seconds);
      iteration_solve.push_back(1e3 * fresh.cpu_solve);
      gmres_its.push_back(fresh.gmres_iterations);
      // At a gradient the factor has not seen: +0.2 % stretch, about one load step of a
      // beat resolved in a few hundred steps (paper §V: 400 steps per beat) ...
      job.Zbar[0] = Z0[0] + o.stale_stretch;
      const proto::JobOutput stale = unit.iterate(job);
      iteration_stale.push_back(1e3 * stale.cpu_seconds);
      gmres_stale.push_back(stale.gmres_iterations);
      // ... and ten times staler, to show how the Krylov work grows.
      job.Zbar[0] = Z0[0] + 10 * o.stale_stretch;
      const proto::JobOutput staler = unit.iterate(job);
      iteration_staler.push_back(1e3 * staler.cpu_seconds);
      gmres_staler.push_back(staler.gmres_iterations);

      // Last, so its 300 MB of factor traffic does not cool the unit's caches above.
      if (cholmod) {
        t = thread_cpu_seconds();
        cholmod->factorize(unit.system().K);
        factorize.push_back(1e3 * (thread_cpu_seconds() - t));
      }
    }
    if (cholmod) *cholmod_ms = median(factorize);
    // One preconditioner application alone (a single-RHS solve with the kept factor):
    // what each GMRES iteration pays besides a product with K.
    std::vector<double> solve;
    const LinearOp M = unit.preconditioner();
    Vec b = Vec::Ones(model->num_dofs()), x(model->num_dofs());
    for (int r = 0; r < std::max(o.repeat, 5); ++r) {
      const double t = thread_cpu_seconds();
      M(b, x);
      solve.push_back(1e3 * (thread_cpu_seconds() - t));
    }

    // A whole Newton solve of a second unit from w = 0 at Z̄ = Z0, refreshing at every
    // iteration: each iteration runs on a fresh factor at the Step 1 tolerance the run
    // would ask there (gmres_forcing), from far (large ‖r‖/r_ref) to converged.
    MicroUnit newton(model);
    json newton_its = json::array();
    std::vector<double> newton_ms;
    proto::JobInput nj;
    nj.step = 1;
    nj.Zbar = Z0;
    nj.apply_update = 1;
    nj.force_refresh = 1;
    bool newton_converged = false;
    for (nj.iteration = 1; nj.iteration <= 12 && !newton_converged; ++nj.iteration) {
      const proto::JobOutput out = newton.iterate(nj);
      const double relative = out.r_norm / out.r_ref;
      // The converged iteration counts: the unit solves Step 1 before the coordinators
      // see that its residual (measured before the solve) has converged.
      newton_converged = relative <= kNewtonRtol;
      newton_ms.push_back(1e3 * (out.cpu_seconds - out.cpu_refresh));
      newton_its.push_back({{"relative_residual", relative},
                            {"step1_rtol", uo.step1_rtol(relative)},
                            {"gmres_iterations", out.gmres_iterations},
                            {"ms", newton_ms.back()}});
    }
    json j = {{"factor", unit.factor()->name()},
              {"assembly_ms", median(assembly)},
              {"iteration_ms", median(iteration)},
              {"iteration_solve_ms", median(iteration_solve)},
              {"iteration_gmres_iterations", median(gmres_its)},
              {"factor_solve_ms", median(solve)},
              {"iteration_stale_ms", median(iteration_stale)},
              {"iteration_stale_gmres_iterations", median(gmres_stale)},
              {"iteration_10x_staler_ms", median(iteration_staler)},
              {"iteration_10x_staler_gmres_iterations", median(gmres_staler)},
              {"newton_fresh_iteration_ms", median(newton_ms)},
              {"newton_fresh", newton_its},
              {"newton_fresh_converged", newton_converged},
              {"refresh_ms", median(refresh)},
              {"refresh_over_factorize", median(refresh) / *cholmod_ms},
              {"first_refresh_with_analysis_ms", first_ms},
              {"factor_MB", unit.factor()->factor_bytes() / 1e6},
              {"factor_Gflop", unit.factor()->factor_flops() / 1e9},
              {"dofs", model->num_dofs()},
              {"elements", model->num_elements()}};
    return j;
  };

  auto cholmod = make_sparse_factor(FactorKind::cholesky);
  double cholmod_ms = 0;
  json j = measure(opt, cholmod.get(), &cholmod_ms);
  j["cholmod_factorize_ms"] = cholmod_ms;
  if (o.single) {
    MicroSolverOptions s = opt;
    s.single_precision = true;
    s.single_factor_mumps = o.single_factor == "mumps";
    s.half_storage = o.single_factor == "half";
    if (o.blr_tolerance > 0 && !s.single_factor_mumps)
      throw InputError(fmt::format("--blr-tolerance {} needs --single-factor mumps (block "
                                   "low-rank is a MUMPS option)", o.blr_tolerance));
    s.blr_tolerance = o.blr_tolerance;
    json js = measure(s, nullptr, &cholmod_ms);
    js.erase("dofs");
    js.erase("elements");
    js["refresh_over_double_refresh"] = js["refresh_ms"].get<double>() / j["refresh_ms"].get<double>();
    js["factor_MB_over_double"] = js["factor_MB"].get<double>() / j["factor_MB"].get<double>();
    js["blr_tolerance"] = o.blr_tolerance;
    j["single"] = js;
  }
  const char* blas = std::getenv("OPENBLAS_NUM_THREADS");
  j["openblas_core"] = core.name;
  j["resolution"] = n;
  j["cell"] = o.cell;
  j["repeat"] = o.repeat;
  j["stale_stretch"] = o.stale_stretch;
  j["gmres_forcing"] = o.gmres_forcing;
  j["OPENBLAS_NUM_THREADS"] = blas ? blas : "unset";
  j["timer"] = "thread CPU time";
  fmt::print("{}\n", j.dump(2));
  return 0;
}

}  // namespace fe2::cli
