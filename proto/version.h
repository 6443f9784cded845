#pragma once
#include <cstdint>

namespace fe2::proto {

/// Bumped whenever any message layout changes. Ranks refuse to talk across versions.
constexpr uint16_t kProtocolVersion = 14;  // 14: JobInput gains settle (--fresh-units); 13: checkpoint step records keep each field's Newton corrections; 12: WorkerStats gains threads; 11: checkpoint step records keep the valve retries, the valve closure its rings' states; 10: checkpoints keep the macro state of the step before (x_{n−1}, Δt_n: BDF2) and each step record's observables; 9: checkpoint step records keep a residual history per macro field; 8: JobOutput gains excess_flops, refresh_flops (collective refresh), Control checkpoint carries with-factors; 7: Control checkpoint, restore; 6: JobOutput gains r_floor; 5: JobOutput and JobCost gain factor_evictions, factor_rebuilt; 4: Control fields, UnitFields; 3: JobInput gains Zbar_dot_coefficient, activation_time; JobOutput active_tension

}  // namespace fe2::proto
