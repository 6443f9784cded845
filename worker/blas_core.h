#pragma once
// Which kernels the BLAS runs, against what the CPU offers. OpenBLAS picks its kernels
// from the CPU model at load time; a model it does not know (common in virtual machines
// and on CPUs newer than the Debian package) falls back to the generic SSE3 "Prescott"
// kernels. On an AVX-512 Xeon (model 207) that made CHOLMOD's factorization of the
// 27,780-DOF unit 3.3× slower (6.5 s against 2.0 s with OPENBLAS_CORETYPE=SkylakeX,
// BENCHMARKS.md, "BLAS kernels"). The choice cannot be changed once the library is
// loaded, so fe2heart says so and names the setting.
#include <string>

namespace fe2 {

struct BlasCore {
  std::string name;      ///< OpenBLAS's core name ("SkylakeX", "Prescott", ...); "" for another BLAS
  std::string cpu;       ///< widest vector extension of this CPU: "avx512", "avx2" or "older"
  std::string suggested; ///< an OPENBLAS_CORETYPE that fits the CPU better; "" when none does
};

BlasCore blas_core();

/// Sets OpenBLAS's threads per call (false for another BLAS, left as it is). A rank whose
/// jobs run on several threads (farm.threads_per_rank) calls BLAS from each: one BLAS
/// thread per call, or the ranks' threads and OpenBLAS's fight for the cores.
bool set_blas_threads(int threads);

/// A warning naming the core, the CPU and the setting; "" when the kernels fit the CPU.
std::string blas_core_warning(const BlasCore& core);

}  // namespace fe2
