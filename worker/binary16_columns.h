#pragma once
// Columns of a factor kept in IEEE binary16, used in float arithmetic without a float
// copy: each entry is widened in a register as it is read (F16C's vcvtph2ps where the
// build targets it). A triangular solve is bound by the bytes it streams, so reading
// 2 bytes per entry instead of 4 is what makes a binary16 factor pay in time as well as
// in memory.

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace fe2 {

/// Rounds to nearest (ties to even); |values| from 65520 on become ±∞ (65504 is the largest).
void floats_to_half(const float* from, uint16_t* to, size_t count);
inline float half_to_float(uint16_t bits) {  // inline: the solves' triangles call it per entry
  _Float16 h;
  std::memcpy(&h, &bits, sizeof h);
  return static_cast<float>(h);
}

/// Most columns the two kernels below take in one pass.
constexpr int kMaxHalfColumns = 4;

/// w[i] −= Σ_c L_c[i] x[c] for i in [0, n), over `ncols` ≤ kMaxHalfColumns columns
/// L_c = columns[c]: the update a forward substitution sends below solved columns.
void subtract_half_columns(int ncols, int n, const uint16_t* const* columns, const float* x,
                           float* w);

/// d[c] = Σ_i L_c[i] w[i] for i in [0, n), over `ncols` ≤ kMaxHalfColumns columns
/// L_c = columns[c]: what a backward substitution gathers from the rows below.
void dot_half_columns(int ncols, int n, const uint16_t* const* columns, const float* w,
                      float* d);

}  // namespace fe2
