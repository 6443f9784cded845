#pragma once
// Checkpoint and restart of a run (common/io/checkpoint_file.h is the file format).
// A checkpoint is taken at a step boundary, after the step's commit:
//   macro   every coordinator's Simulation::save_state (the same everywhere; rank 0's
//           is kept): t, ū and its rates, p, the circulation's state
//   run     the steps behind (summary.json and the beat's periodicity read them) and
//           how far each trace file is
//   units   each point's whole state as its holder serializes it (history, committed
//           Z̄, w, policy counters, the matrix its factor was made of), streamed to
//           rank 0 and written as it arrives
// A restart reads it back on any number of ranks and coordinators: units go to where
// the current policy places them, and a factor is rebuilt from its stored matrix, so
// the continued run is the uninterrupted one bit for bit (with one coordinator; MUMPS
// sums in another order with several). Both the writer and the restarted run start the
// next step with a fresh macro factor, for the same reason.
#include "common/io/checkpoint_file.h"
#include "coordinator/PointEvaluator.h"
#include "coordinator/Simulation.h"
#include "coordinator/farm/Trace.h"
#include "proto/Transport.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace fe2 {

/// The steps behind and the trace offsets, as bytes (the checkpoint's run section).
Bytes pack_run_section(const RunResult& done, const TraceOffsets& trace);
RunResult unpack_run_section(const Bytes& b, TraceOffsets& trace, const std::string& what);

struct CheckpointWritten {
  std::string path;
  uint64_t bytes = 0;
  double seconds = 0.0;
};

/// Writes `path` (rotating the one before to path.previous). `done` and `trace`
/// significant on rank 0. @note Collective on the coordinator group, and on the pure
/// workers through `points`.
CheckpointWritten write_checkpoint(const std::string& path, const RunSpec& spec, int ranks, Simulation& sim,
                                   PointEvaluator& points, const proto::Group& coords, const RunResult& done,
                                   const TraceOffsets& trace);

/// Restores `file` (opened and checked on rank 0, null elsewhere) into `sim` and the
/// points; returns the steps behind, and the trace offsets on rank 0. With
/// `fresh_points` only the macro state is restored: the points keep the initial state
/// they were built in (`fe2heart run --fresh-units`: a beat's phase with other units).
/// @note Collective like write_checkpoint.
RunResult restore_checkpoint(const CheckpointFile* file, Simulation& sim, PointEvaluator& points,
                             const proto::Group& coords, TraceOffsets& trace, bool fresh_points = false);

/// Where the spec a checkpoint ran differs from `now` outside what a restart may change
/// (output, farm, title; with `fresh_points` also a model's `unit`, whose points start
/// afresh): JSON pointers, sorted.
std::vector<std::string> spec_differences(const nlohmann::json& saved, const nlohmann::json& now,
                                          bool fresh_points = false);

}  // namespace fe2
