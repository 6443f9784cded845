#pragma once
// What every fuzz target shares: the one rule (bad input may only end in the reader's
// own error type; anything else — a crash, a sanitizer report, another exception, a
// broken invariant — is a finding) and the input as text or as a file.
#include "common/bytes.h"
#include "common/error.h"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>

namespace fe2::fuzz {

/// Runs `read`; the error type `Expected` (fe2::InputError for user files, fe2::Error
/// for messages between ranks) is the reader refusing the input, which is fine. Any
/// other exception escapes and libFuzzer reports it as a crash with the input.
template <class Expected, class Read>
void expect_only(Read&& read) {
  try {
    read();
  } catch (const Expected&) {
  }
}

/// A property of accepted input that must hold; its failure aborts (a finding).
inline void require(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz property violated: %s\n", what);
  std::abort();
}

inline std::string_view text_of(const uint8_t* data, size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

inline Bytes bytes_of(const uint8_t* data, size_t size) {
  const auto* p = reinterpret_cast<const std::byte*>(data);
  return Bytes(p, p + size);
}

/// The input as a file (for readers that take a path), one per process, rewritten
/// for every input.
inline const std::string& as_file(const uint8_t* data, size_t size, const char* suffix) {
  struct File {  // removed when the process ends normally
    std::string path;
    ~File() { std::remove(path.c_str()); }
  };
  static const File file{std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") +
                         "/fe2_fuzz_" + std::to_string(::getpid()) + suffix};
  std::ofstream(file.path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return file.path;
}

}  // namespace fe2::fuzz
