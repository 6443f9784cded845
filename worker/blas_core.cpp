#include "worker/blas_core.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdlib>
#include <string_view>

// OpenBLAS's own query; weak, so that a build against another BLAS still links (and
// the check is then silent). CMake links libopenblas itself when it is installed.
extern "C" char* openblas_get_corename(void) __attribute__((weak));
extern "C" void openblas_set_num_threads(int) __attribute__((weak));

namespace fe2 {

namespace {
std::string lowercase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return s;
}
}  // namespace

bool set_blas_threads(int threads) {
  if (!openblas_set_num_threads) return false;
  openblas_set_num_threads(threads);
  return true;
}

BlasCore blas_core() {
  BlasCore c;
  if (openblas_get_corename) c.name = openblas_get_corename();
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  const bool avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
  const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else  // OpenBLAS's x86 fallback question does not arise
  const bool avx512 = false, avx2 = false;
#endif
  c.cpu = avx512 ? "avx512" : avx2 ? "avx2" : "older";
  // OpenBLAS's x86 cores without AVX2 kernels (its names, compared case-insensitively).
  constexpr std::array<std::string_view, 12> kPreAvx2 = {
      "prescott", "core2",   "penryn", "dunnington", "nehalem",   "sandybridge",
      "atom",     "katmai", "coppermine", "northwood", "banias", "unknown"};
  const std::string lower = lowercase(c.name);
  const bool generic =
      !c.name.empty() && std::find(kPreAvx2.begin(), kPreAvx2.end(), lower) != kPreAvx2.end();
  if (generic && avx512) c.suggested = "SkylakeX";
  else if (generic && avx2) c.suggested = "Haswell";
  return c;
}

std::string blas_core_warning(const BlasCore& core) {
  if (core.suggested.empty()) return "";
  // A setting OpenBLAS did not take (misspelt, or a core this build lacks) is worth naming.
  const char* set = std::getenv("OPENBLAS_CORETYPE");
  const bool ignored = set && lowercase(set) != lowercase(core.name);
  return fmt::format(
      "OpenBLAS runs its '{}' kernels on a CPU with {}{}: dense factorizations run about 3× "
      "slower than they could. Set OPENBLAS_CORETYPE={} in the environment of every rank "
      "(e.g. mpirun -x OPENBLAS_CORETYPE=...)",
      core.name, core.cpu == "avx512" ? "AVX-512" : "AVX2",
      ignored ? fmt::format(" (OPENBLAS_CORETYPE={} was not taken)", set) : "", core.suggested);
}

}  // namespace fe2
