#pragma once
// What a run leaves in its output folder: the spec it ran, a log, the displacement
// field and per-element stresses as VTU files collected in a PVD (ParaView), and
// summary.json (converged, steps, newton_iterations, probes, per-step history).
// Files are written whole or not at all (write to a temporary name, then rename).
#include "coordinator/Simulation.h"

#include "common/io/vtu_writer.h"

#include <memory>
#include <string>

namespace fe2 {

class RunOutput {
 public:
  /// Creates `dir` (InputError if it cannot) and copies the spec into it.
  RunOutput(const std::string& dir, const RunSpec& spec);
  /// Writes the fields of the current state as step `step` (VTU + PVD entry); `P` is
  /// Simulation::gather_point_stress() (collective, so the caller gathers).
  void write_fields(const Simulation& sim, const std::vector<Vec9>& P, int step, double time);
  /// summary.json; `sim` gives probe positions at the final state.
  void write_summary(const Simulation& sim, const RunResult& result, double wall_seconds);
  const std::string& dir() const { return dir_; }
  std::string pvd_path() const;

 private:
  std::string dir_;
  std::unique_ptr<PvdWriter> pvd_;
};

}  // namespace fe2
