// fe2heart: multi-scale FE² heart simulation. See README.md and `fe2heart --help`.
#include "common/error.h"
#include "tools/commands.h"

#include <CLI/CLI.hpp>
#include <mpi.h>
#include <spdlog/spdlog.h>

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  CLI::App app{"fe2heart: a multi-scale FE² heart simulator (macro tetrahedra driven by "
               "periodic micro units of cardiac cells)"};
  app.require_subcommand(1);
  app.fallthrough();  // --log-level may follow the subcommand
  std::string level = "info";
  app.add_option("--log-level", level, "trace, debug, info, warn, error")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}));

  fe2::cli::RunOptions run;
  auto* c_run = app.add_subcommand("run", "run a scene: writes DIR/summary.json, a log and "
                                          "VTU/PVD fields");
  c_run->add_option("spec", run.spec, "run spec (JSON)")->required();
  c_run->add_option("--out", run.out, "output folder")->required();
  c_run->add_option("--coordinators", run.coordinators,
                    "coordinator ranks (overrides farm.coordinators in the spec)")
      ->check(CLI::Range(1, 1000000));

  std::string validate_spec;
  auto* c_validate = app.add_subcommand("validate", "check a run or unit spec and its meshes");
  c_validate->add_option("spec", validate_spec, "spec (JSON)")->required();

  fe2::cli::UnitOptions unit;
  auto* c_unit = app.add_subcommand(
      "unit", "equilibrate one micro unit under Z̄ (or a sequence) and print JSON with P_bar "
              "(9) and A_hom (81), column-major");
  c_unit->add_option("spec", unit.spec, "unit spec (JSON)")->required();
  c_unit->add_option("--vtu", unit.vtu, "also write the equilibrated unit as VTU");

  fe2::cli::BenchOptions bench;
  auto* c_bench = app.add_subcommand("bench", "benchmarks that print figures (not tests)");
  c_bench->require_subcommand(1);
  auto* c_bench_unit = c_bench->add_subcommand(
      "unit", "time one micro unit: assembly, iteration with a cached factor, refresh");
  c_bench_unit->add_option("--dofs", bench.dofs, "target unit size in DOF")
      ->check(CLI::Range(24, 3000000));
  c_bench_unit->add_option("--repeat", bench.repeat, "repetitions (medians are reported)")
      ->check(CLI::Range(1, 100));
  c_bench_unit->add_option("--stale-stretch", bench.stale_stretch,
                           "fibre stretch between the factored state and the timed iteration")
      ->check(CLI::Range(0.0, 0.2));
  c_bench_unit->add_option("--cell", bench.cell, "cell layout")
      ->check(CLI::IsMember({"two_cells", "homogeneous", "laminate"}));

  int rc = 0;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    rc = app.exit(e);
    MPI_Finalize();
    return rc;
  }
  spdlog::set_level(spdlog::level::from_str(level));
  spdlog::set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");
  try {
    if (*c_run) rc = fe2::cli::run(run);
    else if (*c_validate) rc = fe2::cli::validate(validate_spec);
    else if (*c_unit) rc = fe2::cli::unit(unit);
    else if (*c_bench_unit) rc = fe2::cli::bench_unit(bench);
  } catch (const fe2::Error& e) {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank == 0) spdlog::error("{}", e.what());  // every rank has the same input error
    rc = e.exit_code();
  } catch (const std::exception& e) {
    spdlog::error("unexpected error: {}", e.what());
    rc = 1;
  }
  MPI_Finalize();
  return rc;
}
