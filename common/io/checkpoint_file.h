#pragma once
// A checkpoint file: everything a run needs to continue after a committed step, in the
// project's own versioned binary format (common/bytes.h, the packing unit migration
// already uses). Layout, little-endian:
//
//   "FE2CKPT" 0 | u32 format | u16 protocol | u64 spec hash | string spec text |
//   i32 steps done | f64 time | i32 ranks | i32 coordinators |
//   bytes macro (Simulation::save_state) | bytes run (history, output offsets) |
//   i32 n | n × (i32 unit | bytes state)   (each unit once, in the order they arrived) |
//   u64 FNV-1a of every byte before it
//
// Why not HDF5: a unit's state is already an opaque, versioned byte string (its
// serialize(), which also moves it between ranks), so HDF5 would add a dependency
// and a second description of the same bytes without making them readable by
// anything else; the macro fields users want in ParaView are in the VTU output.
//
// Written atomically: to `path.partial`, checksummed and fsynced, then the current
// `path` becomes `path.previous` and the new one `path`. A reader refuses a file that is
// truncated, corrupted or of another format or protocol version, naming both versions.
#include "common/bytes.h"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace fe2 {

/// Bumped when the layout above changes; a reader refuses any other.
constexpr uint32_t kCheckpointFormat = 1;

struct CheckpointHeader {
  uint32_t format = kCheckpointFormat;
  uint16_t protocol = 0;      ///< proto::kProtocolVersion of the writer (unit state layout)
  uint64_t spec_hash = 0;
  std::string spec_text;      ///< the spec that ran (restart compares it)
  int32_t steps = 0;          ///< steps completed
  double time = 0.0;          ///< t at the end of them
  int32_t ranks = 0, coordinators = 0;  ///< of the run that wrote it (for the record)
  Bytes macro;                ///< the macro state
  Bytes run;                  ///< the run's history and output offsets
};

class CheckpointWriter {
 public:
  /// Opens `path`.partial and writes the header; `units` states must follow.
  CheckpointWriter(std::string path, const CheckpointHeader& header, int units);
  /// Removes the partial file unless finish() completed.
  ~CheckpointWriter();
  CheckpointWriter(const CheckpointWriter&) = delete;
  CheckpointWriter& operator=(const CheckpointWriter&) = delete;

  void add_unit(int unit, const Bytes& state);
  /// Checksum, fsync, then rotates: `path` → `path`.previous, `path`.partial → `path`.
  /// Returns the bytes written.
  uint64_t finish();

 private:
  void write(const void* p, size_t n);
  std::string path_, partial_;
  int fd_ = -1;
  int expected_units_ = 0, units_ = 0;
  uint64_t bytes_ = 0;
  uint64_t hash_ = 0;
  bool finished_ = false;
};

class CheckpointFile {
 public:
  /// Reads and checks the whole file (magic, versions, checksum, framing, each unit
  /// once); an InputError naming the file and what is wrong. `protocol`: this
  /// program's protocol version, which the file's must equal.
  CheckpointFile(std::string path, uint16_t protocol);

  const std::string& path() const { return path_; }
  const CheckpointHeader& header() const { return header_; }
  /// The units in file order.
  std::vector<int> units() const;
  /// One unit's state, read from the file.
  Bytes unit_state(int unit) const;
  uint64_t size() const { return size_; }

 private:
  std::string path_;
  CheckpointHeader header_;
  uint64_t size_ = 0;
  std::vector<std::pair<int, std::pair<uint64_t, uint64_t>>> index_;  ///< unit, (offset, bytes)
  std::vector<int64_t> slot_;  ///< unit -> entry of index_
};

/// The names a run folder's checkpoints have: the newest, and the one before it.
std::string checkpoint_path(const std::string& run_dir);
std::string previous_checkpoint_path(const std::string& run_dir);

/// The checkpoint a restart reads: `where` is a checkpoint file, or a run folder whose
/// newest good checkpoint is taken (checkpoint.bin, else checkpoint.previous.bin);
/// `refused` gets why a newer one was passed over. An InputError if none is usable.
CheckpointFile open_checkpoint(const std::string& where, uint16_t protocol,
                               std::vector<std::string>* refused = nullptr);

}  // namespace fe2
