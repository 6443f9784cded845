#include "common/io/checkpoint_file.h"

#include "common/hash.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace fe2 {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'F', 'E', '2', 'C', 'K', 'P', 'T', '\0'};

std::string errno_text() { return std::strerror(errno); }

/// Opens `path` for reading; its size in `size`.
std::ifstream open_for_reading(const std::string& path, uint64_t& size) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw InputError(fmt::format("checkpoint '{}': no such file", path));
  size = fs::file_size(path, ec);
  if (ec) throw InputError(fmt::format("checkpoint '{}': cannot read its size ({})", path, ec.message()));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("checkpoint '{}': cannot open it ({})", path, errno_text()));
  return in;
}

void read_exactly(std::ifstream& in, void* p, uint64_t n, const std::string& path) {
  in.read(static_cast<char*>(p), static_cast<std::streamsize>(n));
  if (static_cast<uint64_t>(in.gcount()) != n)
    throw InputError(fmt::format("checkpoint '{}': read failed (truncated file?)", path));
}

/// Reads the framing of a checkpoint from a stream, every read checked against `end`.
class FileReader {
 public:
  FileReader(std::ifstream& in, const std::string& path, uint64_t end, uint64_t at)
      : in_(in), path_(path), end_(end), at_(at) {}
  template <class T>
  T get() {
    T v;
    need(sizeof v);
    read_exactly(in_, &v, sizeof v, path_);
    at_ += sizeof v;
    return v;
  }
  /// An array written by ByteWriter::put_array of bytes (or chars).
  template <class Container>
  Container get_bytes() {
    const auto n = get<uint64_t>();
    need(n);
    Container c;
    c.resize(n);
    read_exactly(in_, c.data(), n, path_);
    at_ += n;
    return c;
  }
  void skip(uint64_t n) {
    need(n);
    at_ += n;
    in_.seekg(static_cast<std::streamoff>(at_));
  }
  uint64_t offset() const { return at_; }
  uint64_t remaining() const { return end_ - at_; }

 private:
  void need(uint64_t n) const {
    if (n > end_ - at_)
      throw InputError(fmt::format("checkpoint '{}': a field of {} bytes at offset {} runs past the end of "
                                   "the file ({} bytes of content): truncated or corrupted", path_, n, at_, end_));
  }
  std::ifstream& in_;
  const std::string& path_;
  uint64_t end_, at_;
};

}  // namespace

// ---------------------------------------------------------------------------- writer

CheckpointWriter::CheckpointWriter(std::string path, const CheckpointHeader& h, int units)
    : path_(std::move(path)), partial_(path_ + ".partial"), expected_units_(units) {
  fd_ = ::open(partial_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw Error(fmt::format("checkpoint '{}': cannot create it ({})", partial_, errno_text()));
  Fnv1a empty;
  hash_ = empty.value();
  Bytes b;
  b.reserve(128 + h.spec_text.size() + h.macro.size() + h.run.size());
  ByteWriter w(b);
  w.put_raw(kMagic, sizeof kMagic);
  w.put(h.format);
  w.put(h.protocol);
  w.put(h.spec_hash);
  w.put_string(h.spec_text);
  w.put(h.steps);
  w.put(h.time);
  w.put(h.ranks);
  w.put(h.coordinators);
  w.put_array(h.macro.data(), h.macro.size());
  w.put_array(h.run.data(), h.run.size());
  w.put<int32_t>(units);
  write(b.data(), b.size());
}

CheckpointWriter::~CheckpointWriter() {
  if (fd_ >= 0) ::close(fd_);
  if (!finished_) ::unlink(partial_.c_str());  // never mistaken for a whole checkpoint
}

void CheckpointWriter::write(const void* p, size_t n) {
  // FNV-1a over the stream, continued from the previous chunk.
  const auto* c = static_cast<const unsigned char*>(p);
  uint64_t h = hash_;
  for (size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 1099511628211ull;
  hash_ = h;
  size_t done = 0;
  while (done < n) {
    const ssize_t k = ::write(fd_, c + done, n - done);
    if (k < 0) {
      if (errno == EINTR) continue;
      throw Error(fmt::format("checkpoint '{}': write failed ({})", partial_, errno_text()));
    }
    done += static_cast<size_t>(k);
  }
  bytes_ += n;
}

void CheckpointWriter::add_unit(int unit, const Bytes& state) {
  FE2_CHECK(units_ < expected_units_, "checkpoint '{}': more than the {} unit states announced", partial_,
            expected_units_);
  Bytes b;
  b.reserve(16);
  ByteWriter w(b);
  w.put<int32_t>(unit);
  w.put<uint64_t>(state.size());
  write(b.data(), b.size());
  write(state.data(), state.size());
  ++units_;
}

uint64_t CheckpointWriter::finish() {
  FE2_CHECK(units_ == expected_units_, "checkpoint '{}': {} unit states written, {} announced", partial_,
            units_, expected_units_);
  const uint64_t checksum = hash_;
  write(&checksum, sizeof checksum);
  if (::fsync(fd_) != 0) throw Error(fmt::format("checkpoint '{}': fsync failed ({})", partial_, errno_text()));
  ::close(fd_);
  fd_ = -1;
  // The newest whole checkpoint stays on disk until the new one is whole too.
  const std::string previous = path_ + ".previous";
  std::error_code ec;
  if (fs::exists(path_, ec) && std::rename(path_.c_str(), previous.c_str()) != 0)
    throw Error(fmt::format("checkpoint: cannot rename '{}' to '{}' ({})", path_, previous, errno_text()));
  if (std::rename(partial_.c_str(), path_.c_str()) != 0)
    throw Error(fmt::format("checkpoint: cannot rename '{}' to '{}' ({})", partial_, path_, errno_text()));
  finished_ = true;
  // The renames themselves must survive a crash: sync the folder.
  const std::string dir = fs::path(path_).parent_path().empty() ? "." : fs::path(path_).parent_path().string();
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
  return bytes_;
}

// ---------------------------------------------------------------------------- reader

CheckpointFile::CheckpointFile(std::string path, uint16_t protocol) : path_(std::move(path)) {
  std::ifstream in = open_for_reading(path_, size_);
  const std::string what = fmt::format("checkpoint '{}'", path_);
  if (size_ < sizeof kMagic + sizeof(uint32_t) + sizeof(uint64_t))
    throw InputError(fmt::format("{}: {} bytes is too short to be a checkpoint (truncated?)", what, size_));
  char magic[sizeof kMagic];
  read_exactly(in, magic, sizeof magic, path_);
  if (std::memcmp(magic, kMagic, sizeof kMagic) != 0)
    throw InputError(fmt::format("{}: not an fe2heart checkpoint (wrong magic bytes)", what));
  uint32_t format = 0;
  read_exactly(in, &format, sizeof format, path_);
  if (format != kCheckpointFormat)
    throw InputError(fmt::format("{}: written in checkpoint format {}; this fe2heart reads format {} only",
                                 what, format, kCheckpointFormat));

  // The checksum over everything before its last 8 bytes, read in chunks.
  in.seekg(0);
  Fnv1a hash;
  std::vector<char> chunk(1 << 20);
  for (uint64_t left = size_ - sizeof(uint64_t); left > 0;) {
    const uint64_t n = std::min<uint64_t>(left, chunk.size());
    read_exactly(in, chunk.data(), n, path_);
    hash.add(chunk.data(), n);
    left -= n;
  }
  uint64_t stored = 0;
  read_exactly(in, &stored, sizeof stored, path_);
  if (stored != hash.value())
    throw InputError(fmt::format("{}: checksum mismatch (stored {:016x}, computed {:016x}): the file is "
                                 "truncated or corrupted", what, stored, hash.value()));

  // The header, then the unit index (offsets only: states are read on demand, so a
  // reader never holds more than one unit's state).
  in.seekg(sizeof kMagic);
  FileReader r(in, path_, size_ - sizeof(uint64_t), sizeof kMagic);
  CheckpointHeader& h = header_;
  h.format = r.get<uint32_t>();
  h.protocol = r.get<uint16_t>();
  if (h.protocol != protocol)
    throw InputError(fmt::format("{}: written by fe2heart protocol version {}; this fe2heart is version {} "
                                 "and cannot read another version's unit states",
                                 what, h.protocol, protocol));
  h.spec_hash = r.get<uint64_t>();
  h.spec_text = r.get_bytes<std::string>();
  h.steps = r.get<int32_t>();
  h.time = r.get<double>();
  h.ranks = r.get<int32_t>();
  h.coordinators = r.get<int32_t>();
  h.macro = r.get_bytes<Bytes>();
  h.run = r.get_bytes<Bytes>();
  const auto units = r.get<int32_t>();
  if (h.steps < 0 || units < 0 || !std::isfinite(h.time))
    throw InputError(fmt::format("{}: invalid header ({} steps, {} units, t = {})", what, h.steps, units, h.time));
  if (static_cast<uint64_t>(units) > r.remaining() / 12)
    throw InputError(fmt::format("{}: {} unit states cannot fit in the {} bytes left", what, units, r.remaining()));
  slot_.assign(static_cast<size_t>(units), -1);
  for (int k = 0; k < units; ++k) {
    const auto unit = r.get<int32_t>();
    const auto bytes = r.get<uint64_t>();
    if (unit < 0 || unit >= units || slot_[static_cast<size_t>(unit)] >= 0)
      throw InputError(fmt::format("{}: unit {} out of range [0, {}) or stored twice", what, unit, units));
    slot_[static_cast<size_t>(unit)] = static_cast<int64_t>(index_.size());
    index_.push_back({unit, {r.offset(), bytes}});
    r.skip(bytes);
  }
  if (r.remaining() != 0)
    throw InputError(fmt::format("{}: {} bytes after the last unit state", what, r.remaining()));
}

std::vector<int> CheckpointFile::units() const {
  std::vector<int> u;
  u.reserve(index_.size());
  for (const auto& e : index_) u.push_back(e.first);
  return u;
}

Bytes CheckpointFile::unit_state(int unit) const {
  FE2_CHECK(unit >= 0 && static_cast<size_t>(unit) < slot_.size() && slot_[unit] >= 0,
            "checkpoint '{}' holds no state of unit {}", path_, unit);
  const auto [offset, bytes] = index_[static_cast<size_t>(slot_[unit])].second;
  uint64_t size = 0;
  std::ifstream in = open_for_reading(path_, size);
  if (size != size_) throw InputError(fmt::format("checkpoint '{}' changed while it was read", path_));
  in.seekg(static_cast<std::streamoff>(offset));
  Bytes b(bytes);
  read_exactly(in, b.data(), bytes, path_);
  return b;
}

std::string checkpoint_path(const std::string& run_dir) { return (fs::path(run_dir) / "checkpoint.bin").string(); }
std::string previous_checkpoint_path(const std::string& run_dir) { return checkpoint_path(run_dir) + ".previous"; }

CheckpointFile open_checkpoint(const std::string& where, uint16_t protocol, std::vector<std::string>* refused) {
  std::error_code ec;
  if (!fs::is_directory(where, ec)) return CheckpointFile(where, protocol);
  std::vector<std::string> why;
  for (const std::string& path : {checkpoint_path(where), previous_checkpoint_path(where)}) {
    if (!fs::exists(path, ec)) continue;
    try {
      CheckpointFile f(path, protocol);
      if (refused) {
        *refused = why;
        for (std::string& w : *refused) w += fmt::format("; using '{}' (after step {}) instead", path, f.header().steps);
      }
      return f;
    } catch (const InputError& e) {
      why.push_back(e.what());
    }
  }
  if (why.empty())
    throw InputError(fmt::format("--restart '{}': no checkpoint in this folder (checkpoint.bin; a run writes "
                                 "one with output.checkpoint_every or on SIGTERM/SIGUSR1)", where));
  std::string all;
  for (const std::string& w : why) all += "\n  " + w;
  throw InputError(fmt::format("--restart '{}': no usable checkpoint:{}", where, all));
}

}  // namespace fe2
