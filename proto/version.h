#pragma once
#include <cstdint>

namespace fe2::proto {

/// Bumped whenever any message layout changes. Ranks refuse to talk across versions.
constexpr uint16_t kProtocolVersion = 2;

}  // namespace fe2::proto
