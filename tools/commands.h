#pragma once
// The fe2heart subcommands; each returns the process exit code.
#include <optional>
#include <string>
#include <vector>

namespace fe2 {
struct SchemaNode;
}

namespace fe2::cli {

struct RunOptions {
  std::string spec;
  std::string out;
  int coordinators = 0;  ///< 0: from the spec
  int threads_per_rank = 0;  ///< 0: from the spec
  std::string policy;    ///< empty: from the spec
  std::string memory_limit;  ///< "8G", "500M", bytes; empty: the available memory
  bool overwrite = false;  ///< replace an earlier run in `out` (else refuse, exit 2)
  std::string restart;     ///< a checkpoint file or a run folder to continue from
  bool force = false;      ///< restart although the spec changed beyond output/farm
  int beats = 0;           ///< > 0: replaces the spec's time.beats (a spec of whole beats)
  bool fresh_units = false;  ///< --restart the macro state only: the points start afresh
  int stop_after_steps = 0;  ///< > 0: stop after this many steps of this run, checkpointed
  std::string stop_file;     ///< once this file exists: stop as on SIGUSR1 (checkpointed)
};
int run(const RunOptions& o);
/// `memory_limit` as in RunOptions.
int validate(const std::string& spec, const std::string& memory_limit = "");

struct UnitOptions {
  std::string spec;
  std::string vtu;  ///< optional: write the equilibrated unit mesh here
};
int unit(const UnitOptions& o);

struct BenchOptions {
  int dofs = 26000;
  int repeat = 5;
  std::string cell = "two_cells";
  double stale_stretch = 0.002;  ///< how far Z̄ moves from the factored state
  bool single = false;           ///< also time a unit with a single-precision factor
  std::string single_factor = "supernodal";  ///< which: "supernodal" or "mumps"
  double blr_tolerance = 0.0;    ///< MUMPS's block low-rank threshold (0: full rank)
  std::string gmres_forcing = "residual";  ///< Step 1 tolerance: "constant" or "residual"
};
int bench_unit(const BenchOptions& o);
/// `fe2heart bench blas`: OpenBLAS's kernels, the CPU's vector extension and a better
/// OPENBLAS_CORETYPE if there is one (worker/blas_core.h); only that with suggested_only.
int bench_blas(bool suggested_only);

struct CirculationOptions {
  std::string spec;
  std::string out;
  bool overwrite = false;  ///< replace an earlier run in `out` (else refuse, exit 2)
};
/// A 0D circulation alone with elastance ventricles (tools/cmd_circulation.cpp).
int circulation(const CirculationOptions& o);
/// `validate` of a standalone circulation spec.
int validate_circulation(const std::string& spec);

/// A kind of spec file and its schema (what spec-doc and spec-schema print).
struct SpecKind {
  const char* name;     ///< "run", "unit", "circulation", "study" (spec-schema --NAME)
  const char* heading;  ///< spec-doc's section title
  const SchemaNode* schema;
  const char* id;       ///< JSON Schema $id
  const char* title;
};
/// Every kind, in spec-doc's order.
const std::vector<SpecKind>& spec_kinds();
/// Every spec key (from the schemas): type, default or "required", range, help; as
/// markdown tables with `markdown` (docs/spec-reference.md).
int spec_doc(bool markdown);
/// JSON Schema 2020-12 of the spec kind `kind` (SpecKind::name).
int spec_schema(const std::string& kind);

int trace_summary(const std::string& dir, bool as_json);
int trace_plot(const std::string& dir, const std::string& out);

/// Farm settings left unset are the run's own (its DIR/spec.json "farm" section).
struct FarmSimOptions {
  std::string dir;
  std::vector<int> workers;                     ///< empty: 6144, 60000, 600000
  std::vector<int> units_per_worker = {1, 4};
  std::optional<std::string> policy, rebalance_at;
  std::optional<double> latency, bandwidth, min_gain, tolerated_imbalance;
  std::optional<int> batch;
  double macro_scale = 1.0;
  /// Another run's folder: its macro costs per Newton iteration (by kind: factorizing,
  /// kept-factor, no solve) replace the replayed run's (a macro of another size).
  std::string macro_from;
  /// A full beat of the same heart (e.g. with cheaper units): extrapolate the replay to
  /// one beat's seconds and core-hours over its phases (coordinator/farm/beat_projection.h).
  std::string beat;
  /// Replay each job at its kind's median cost in its iteration × its unit's persistent
  /// factor: the run without the measuring machine's timing noise (timing_noise.h).
  bool without_timing_noise = false;
  long long max_units = 3000000;
};
int farm_sim(const FarmSimOptions& o);

/// `fe2heart study`: variants of a base spec run, costed and compared (tools/cmd_study.cpp).
struct StudyOptions {
  std::string spec;
  std::string out;
  int np = 0;  ///< 0: the study file's "np"
  bool overwrite = false;
  bool resume = false;  ///< keep the variants an earlier study in --out finished with the same spec
};
int study(const StudyOptions& o);
/// `validate` of a study file: the study and every variant's run spec; runs nothing.
int validate_study(const std::string& file);

}  // namespace fe2::cli
