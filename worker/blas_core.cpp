#include "worker/blas_core.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <string_view>

// OpenBLAS's own query; weak, so that a build against another BLAS still links.
extern "C" char* openblas_get_corename(void) __attribute__((weak));

namespace fe2 {

BlasCore blas_core() {
  BlasCore c;
  if (openblas_get_corename) c.name = openblas_get_corename();
  __builtin_cpu_init();
  const bool avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
  const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  c.cpu = avx512 ? "avx512" : avx2 ? "avx2" : "older";
  // OpenBLAS's x86 cores without AVX2 kernels (its names, compared case-insensitively).
  constexpr std::array<std::string_view, 12> kPreAvx2 = {
      "prescott", "core2",   "penryn", "dunnington", "nehalem",   "sandybridge",
      "atom",     "katmai", "coppermine", "northwood", "banias", "unknown"};
  std::string lower = c.name;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  const bool generic =
      !c.name.empty() && std::find(kPreAvx2.begin(), kPreAvx2.end(), lower) != kPreAvx2.end();
  if (generic && avx512) c.suggested = "SkylakeX";
  else if (generic && avx2) c.suggested = "Haswell";
  return c;
}

std::string blas_core_warning(const BlasCore& core) {
  if (core.suggested.empty()) return "";
  const char* set = std::getenv("OPENBLAS_CORETYPE");
  return fmt::format(
      "OpenBLAS runs its '{}' kernels on a CPU with {}{}: dense factorizations run about 3× "
      "slower than they could. Set OPENBLAS_CORETYPE={} in the environment of every rank "
      "(e.g. mpirun -x OPENBLAS_CORETYPE=...)",
      core.name, core.cpu == "avx512" ? "AVX-512" : "AVX2",
      set ? fmt::format(" (OPENBLAS_CORETYPE={} was not taken)", set) : "", core.suggested);
}

}  // namespace fe2
