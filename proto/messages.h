#pragma once
// Every message between fe2heart ranks, each one small type with pack / unpack, and a
// validate that runs on receipt (after preCICE's SerializedMesh). Wire layout:
//
//   header   u16 protocol version | u16 message type
//   Hello    u64 spec hash | i32 rank | i32 ranks
//   Control  u8 command | i32 step | i32 iteration | f64 time | f64 dt |
//            u64 n moves | n × (i32 unit, i32 from, i32 to) | u8 with_factors
//   Pull     i32 worker | i32 max_jobs | u64 n | n × JobOutput   (results + next request)
//   Batch    u8 done | u64 n | n × JobInput
//   Stats    WorkerStats (fixed-size record)
//   State    i32 unit | u64 n | n bytes (a unit's serialized state)
//   Costs    i32 step | i32 iteration | u64 n | n × JobCost   (coordinator k -> 0, gathered)
//   Fields   i32 unit | i32 step | 9 f64 Z̄ | 9 f64 P̄ | u8 active |
//            u64 3n, 3n f64 w per node | u64 9m, 9m f64 P per cell |
//            u64 m, m f64 det F per cell | u64 m, m f64 T_a per cell   (holder -> rank 0)
//   JobInput  = i32 unit, step, iteration | f64 time, dt | u8 apply_update, force_refresh |
//               9 f64 Z̄ | 9 f64 Ż̄ | f64 ∂Ż̄/∂Z̄ | f64 t_act             (kJobInputBytes)
//   JobOutput = i32 unit | 81 f64 𝔸_hom | 9 f64 P̃ | 9 f64 P̄ | f64 r_norm, r_ref, r_floor |
//               i32 gmres | u8 kind | 4 f64 cpu (job, assembly, refresh, solve) |
//               u8 next_refresh | u64 state_bytes | f64 T_a | i32 factor_evictions |
//               u8 factor_rebuilt | f64 excess_flops, refresh_flops | u8 status |
//               message string                                    (kJobOutputBytes + text)
//   JobCost   = i32 unit | u8 kind | i32 gmres | f64 cpu, cpu_refresh | u8 next_refresh |
//               u64 state_bytes | i32 factor_evictions | u8 factor_rebuilt | u8 failed
//                                                                   (kJobCostBytes)
// Little-endian, native doubles: all ranks of one job run on one architecture.
#include "common/bytes.h"
#include "proto/job.h"
#include "proto/version.h"

#include <string>
#include <vector>

namespace fe2::proto {

enum class Type : uint16_t { hello = 1, control = 2, pull = 3, batch = 4, stats = 5, state = 6, costs = 7,
                            unit_fields = 8 };

/// The message type's name, as errors print it ("Pull", "Batch", ...).
const char* name_of(Type t);

/// Point-to-point tags; one per message type.
constexpr int tag_of(Type t) { return 100 + static_cast<int>(t); }

constexpr size_t kJobInputBytes = 3 * 4 + 2 * 8 + 2 + 18 * 8 + 2 * 8 + 1;
constexpr size_t kJobOutputBytes = 4 + (81 + 9 + 9 + 3) * 8 + 4 + 1 + 4 * 8 + 1 + 8 + 8 + 4 + 1 + 2 * 8 + 1;
constexpr size_t kJobCostBytes = 4 + 1 + 4 + 2 * 8 + 1 + 8 + 4 + 1 + 1;

/// Reads and checks the header; throws fe2::Error naming both versions on mismatch.
void check_header(ByteReader& r, Type expected);

struct Hello {
  uint64_t spec_hash = 0;
  int32_t rank = 0, ranks = 0;
  void pack(Bytes& out) const;
  static Hello unpack(const Bytes& in);
};

/// `fields`: after a step's converged iteration and before its commit, the holder of
/// each unit in `moves` (unit, from = holder, to = rank 0) sends it its UnitFields.
/// `checkpoint`: at a step boundary, the holder of each unit in `moves` (from = holder,
/// to = rank 0) sends it a copy of the unit's state (a State message) and keeps the unit.
/// `restore`: rank 0 sends each unit in `moves` (from = 0, to = holder), in that order,
/// the state read from a checkpoint; the holder replaces its unit's state with it.
enum class Command : uint8_t { iterate = 1, commit = 2, rollback = 3, rebalance = 4, shutdown = 5,
                               fields = 6, checkpoint = 7, restore = 8 };
constexpr uint8_t kLastCommand = 8;

struct Move {
  int32_t unit, from, to;
};

struct Control {
  Command command = Command::shutdown;
  int32_t step = 0, iteration = 0;
  double time = 0.0, dt = 0.0;
  std::vector<Move> moves;  ///< rebalance (units to move) and fields (units to report)
  /// checkpoint: the states carry the units' numeric factors (output.checkpoint_factors); 0 or 1
  uint8_t with_factors = 0;
  void pack(Bytes& out) const;
  static Control unpack(const Bytes& in);
};

/// A worker's results for its last batch from this coordinator, and its request for
/// up to `max_jobs` more.
struct Pull {
  int32_t worker = -1;
  int32_t max_jobs = 1;
  std::vector<JobOutput> results;
  void pack(Bytes& out) const;
  static Pull unpack(const Bytes& in);
};

/// Jobs for one worker; `done` means this coordinator has nothing more for it in this
/// iteration (and has all its results).
struct Batch {
  bool done = false;
  std::vector<JobInput> jobs;
  void pack(Bytes& out) const;
  static Batch unpack(const Bytes& in);
};

/// One worker's account of one Newton iteration (traces, paper §IV-C).
struct WorkerStats {
  int32_t worker = -1, step = 0, iteration = 0;
  int32_t units_held = 0, jobs = 0;
  int32_t migrations_in = 0, migrations_out = 0;
  double t_begin = 0.0, t_end = 0.0;   ///< wall clock of the micro phase on this worker
  int32_t threads = 1;                 ///< threads running jobs on this rank (farm.threads_per_rank)
  double busy_cpu = 0.0;               ///< CPU seconds in unit jobs, summed over the threads
  double busy_wall = 0.0;              ///< wall seconds in unit jobs, summed over the threads
  double wait_wall = 0.0;              ///< blocked waiting for batches (comm1 as seen here)
  int64_t bytes_sent = 0, bytes_received = 0;
  void pack(Bytes& out) const;
  static WorkerStats unpack(const Bytes& in);
};

struct UnitState {
  int32_t unit = -1;
  Bytes state;
  void pack(Bytes& out) const;
  static UnitState unpack(const Bytes& in);
};

/// A micro unit's fields at the converged state of a step (paper Fig. 11), in the unit's
/// own frame: the fluctuation w at every micro mesh node (0 at the pinned node;
/// displacement = Z̄·X + w), and per micro element the volume mean of the first
/// Piola stress over its Gauss points, the mean det F and (when the unit's cells
/// contract) the mean T_a. The cell volume average of P equals P̄.
struct UnitFields {
  int32_t unit = -1;
  int32_t step = 0;               ///< output step (1 = after the first time step)
  Vec9 Zbar = Vec9::Zero();       ///< Z̄_μ of the state
  Vec9 P_bar = Vec9::Zero();      ///< ⟨Π⟩ the unit reported for it
  bool active = false;            ///< some cell contracts (active_tension is meaningful)
  std::vector<double> w;          ///< 3 per node, node after node
  std::vector<double> P;          ///< 9 per cell (column-major, as Vec9)
  std::vector<double> det_F;      ///< 1 per cell
  std::vector<double> active_tension;  ///< 1 per cell (Pa), 0 outside contracting cells
  int nodes() const { return static_cast<int>(w.size() / 3); }
  int cells() const { return static_cast<int>(det_F.size()); }
  void pack(Bytes& out) const;
  /// Checks sizes agree (3n, 9m, m, m) and every number is finite.
  static UnitFields unpack(const Bytes& in);
};

/// What the scheduler's cost model and the unit trace need of one job: a JobOutput
/// without its tensors (about 30 bytes instead of 800).
struct JobCost {
  int32_t unit = -1;
  Refresh kind = Refresh::reuse;
  int32_t gmres_iterations = 0;
  double cpu_seconds = 0.0;     ///< whole job
  double cpu_refresh = 0.0;     ///< its factorization and χ, if any
  uint8_t next_refresh = 0;     ///< NextJob bits
  uint64_t state_bytes = 0;
  int32_t factor_evictions = 0; ///< JobOutput::factor_evictions
  uint8_t factor_rebuilt = 0;   ///< JobOutput::factor_rebuilt
  uint8_t failed = 0;
  static JobCost of(const JobOutput& o);
};

/// One coordinator's job costs of one Newton iteration, gathered on coordinator 0.
struct CostReport {
  int32_t step = 0, iteration = 0;
  std::vector<JobCost> jobs;
  void pack(Bytes& out) const;
  static CostReport unpack(const Bytes& in);
};

void pack_job(ByteWriter& w, const JobInput& j);
JobInput unpack_job(ByteReader& r);
void pack_result(ByteWriter& w, const JobOutput& o);
JobOutput unpack_result(ByteReader& r);

}  // namespace fe2::proto
