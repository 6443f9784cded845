#pragma once
// What a run leaves in its output folder: the spec it ran, a log, the displacement
// field and per-element stresses as VTU files collected in a PVD (ParaView), and
// summary.json (complete, converged, steps, newton_iterations, probes, per-step
// history). Files are written whole or not at all (write to a temporary name, then
// rename), and summary.json is rewritten after every step, so a killed run still
// leaves a readable summary of the steps it finished ("complete": false).
#include "coordinator/Simulation.h"

#include "common/io/vtu_writer.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace fe2 {

/// Whether `name` (a file name, no folder) is one of the files a run or `fe2heart
/// trace plot` writes into a run folder (summary.json, spec.json, fe2heart.log,
/// displacement.pvd, displacement_NNNNN.vtu, trace_*.jsonl, the trace PNGs, and the
/// ".tmp" names they are written under), or, as "units/<name>", one of the unit files
/// of output.units in the units/ subfolder (unit_K.pvd, unit_K_NNNNN.vtu).
bool is_run_output_file(const std::string& name);

/// The run-output files in `dir` and its units/ subfolder (sorted names relative to
/// `dir`; empty if `dir` does not exist).
std::vector<std::string> run_output_files(const std::string& dir);

class RunOutput {
 public:
  /// Creates `dir` (InputError if it cannot), removes the files of an earlier run
  /// from it (tools/output_folder.h has allowed that; other files are left alone),
  /// copies the spec into it and writes an incomplete summary.json.
  /// With `resume` (a restart into the folder of the run it continues) nothing of the
  /// earlier run is removed, and resume() takes up its series and summary.
  RunOutput(const std::string& dir, const RunSpec& spec, bool resume = false);
  /// A restart: the PVD lists again the VTUs of the steps behind (`done`, those of
  /// `is_output_step` whose file is in the folder), and the summary continues them.
  void resume(const RunResult& done, const std::function<bool(int step)>& is_output_step);
  /// The steps so far (write_progress), for checkpoints.
  const RunResult& progress() const { return progress_; }
  /// Writes the fields of the current state as step `step` (VTU + PVD entry); `P` is
  /// Simulation::gather_point_fields() (collective, so the caller gathers).
  void write_fields(const Simulation& sim, const PointFields& fields, int step, double time);
  /// After each accepted step: rewrites summary.json with "complete": false and the
  /// steps so far (probes at the current state).
  void write_progress(const Simulation& sim, const StepRecord& step, double wall_seconds);
  /// At the end, converged or not: summary.json with "complete": true; `sim` gives
  /// probe positions at the final state.
  void write_summary(const Simulation& sim, const RunResult& result, double wall_seconds);
  const std::string& dir() const { return dir_; }
  std::string pvd_path() const;

 private:
  void write(const Simulation& sim, const RunResult& result, double wall_seconds, bool complete);
  /// summary.json's "circulation" (beat_report.h) into `s`; with `complete` also circulation.csv.
  void write_circulation(const RunSpec& spec, const RunResult& result, bool complete, json& s) const;
  std::string dir_;
  std::unique_ptr<PvdWriter> pvd_;
  RunResult progress_;  ///< the steps so far, for write_progress
  std::vector<double> reference_volumes_;  ///< per spec.cavities, undeformed
};

}  // namespace fe2
