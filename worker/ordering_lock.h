#pragma once
// One fill-reducing ordering at a time per process. CHOLMOD's analysis may call METIS,
// and Debian's libmetis5 draws its random choices from libc rand(), reseeded at each
// call: two analyses at once on two threads (farm.threads_per_rank) would interleave
// their draws, and a unit's ordering — so its factor's round-off, so its answer's last
// bits — would depend on the schedule. Serialized, every analysis sees the sequence it
// sees alone. (An analysis is once per unit factor pattern: the lock costs nothing.)
#include <mutex>

namespace fe2 {

inline std::mutex& ordering_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace fe2
