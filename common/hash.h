#pragma once
// FNV-1a, 64 bit: a cheap content fingerprint (spec text, unit models), identical on
// every rank and every run. Not for security.
#include <cstddef>
#include <cstdint>

namespace fe2 {

class Fnv1a {
 public:
  void add(const void* data, size_t bytes) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) h_ = (h_ ^ b[i]) * 1099511628211ull;
  }
  uint64_t value() const { return h_; }

 private:
  uint64_t h_ = 1469598103934665603ull;
};

}  // namespace fe2
