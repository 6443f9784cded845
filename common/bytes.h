#pragma once
// Byte packing for unit state, checkpoints and messages: a writer that appends
// trivially-copyable values and arrays, and a reader that checks every read against
// the buffer's end (a truncated or corrupted buffer is an fe2::Error, never a crash).
#include "common/error.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace fe2 {

using Bytes = std::vector<std::byte>;

class ByteWriter {
 public:
  explicit ByteWriter(Bytes& out) : out_(out) {}
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put_raw(&v, sizeof(T));
  }
  template <class T>
  void put_array(const T* p, size_t n) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<uint64_t>(n);
    put_raw(p, n * sizeof(T));
  }
  void put_string(const std::string& s) { put_array(s.data(), s.size()); }
  void put_raw(const void* p, size_t n) {
    const size_t at = out_.size();
    out_.resize(at + n);
    if (n) std::memcpy(out_.data() + at, p, n);
  }

 private:
  Bytes& out_;
};

class ByteReader {
 public:
  ByteReader(const std::byte* p, size_t n, std::string what) : p_(p), end_(p + n), what_(std::move(what)) {}
  explicit ByteReader(const Bytes& b, std::string what) : ByteReader(b.data(), b.size(), std::move(what)) {}

  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    get_raw(&v, sizeof(T));
    return v;
  }
  /// Reads an array written by put_array; `expected` >= 0 also checks its length.
  template <class T>
  std::vector<T> get_array(int64_t expected = -1) {
    const uint64_t n = get<uint64_t>();
    if (expected >= 0 && n != static_cast<uint64_t>(expected))
      throw Error(fmt::format("{}: array of {} entries where {} were expected", what_, n, expected));
    if (n > remaining() / sizeof(T))
      throw Error(fmt::format("{}: array of {} entries runs past the end of the buffer", what_, n));
    std::vector<T> v(n);
    get_raw(v.data(), n * sizeof(T));
    return v;
  }
  template <class T>
  void get_array_into(T* p, size_t expected) {
    const uint64_t n = get<uint64_t>();
    if (n != expected)
      throw Error(fmt::format("{}: array of {} entries where {} were expected", what_, n, expected));
    get_raw(p, n * sizeof(T));
  }
  std::string get_string() {
    auto v = get_array<char>();
    return std::string(v.begin(), v.end());
  }
  void get_raw(void* dst, size_t n) {
    if (n > remaining())
      throw Error(fmt::format("{}: truncated buffer (need {} more bytes, {} left)", what_, n,
                              remaining()));
    if (n) std::memcpy(dst, p_, n);
    p_ += n;
  }
  size_t remaining() const { return static_cast<size_t>(end_ - p_); }
  bool at_end() const { return p_ == end_; }
  const std::string& what() const { return what_; }

 private:
  const std::byte* p_;
  const std::byte* end_;
  std::string what_;
};

}  // namespace fe2
