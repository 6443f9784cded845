#include "worker/binary16_columns.h"

#include "common/error.h"

#include <cstring>
#include <type_traits>
#ifdef __F16C__
#include <immintrin.h>
#endif
#if defined(__F16C__) && defined(__FMA__)
#define FE2_HALF_VECTORS 1  // 8 entries per instruction; the scalar loops finish the tails
#endif

namespace fe2 {

void floats_to_half(const float* from, uint16_t* to, size_t count) {
  size_t i = 0;
#ifdef __F16C__
  for (; i + 8 <= count; i += 8)
    _mm_storeu_si128(reinterpret_cast<__m128i*>(to + i),
                     _mm256_cvtps_ph(_mm256_loadu_ps(from + i), _MM_FROUND_TO_NEAREST_INT));
#endif
  for (; i < count; ++i) {
    const _Float16 h = static_cast<_Float16>(from[i]);
    std::memcpy(to + i, &h, sizeof h);
  }
}

namespace {

#ifdef FE2_HALF_VECTORS
inline __m256 widen(const uint16_t* p) {
  return _mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}

inline float sum_lanes(__m256 v) {
  __m128 s = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  s = _mm_add_ps(s, _mm_movehl_ps(s, s));
  s = _mm_add_ss(s, _mm_movehdup_ps(s));
  return _mm_cvtss_f32(s);
}
#endif

// The columns are a compile-time count so their widened entries and x stay in registers:
// per 8 rows, C loads of 16 bytes and one load and store of w.
template <int C>
void subtract_columns(int n, const uint16_t* const* L, const float* x, float* w) {
  int i = 0;
#ifdef FE2_HALF_VECTORS
  __m256 xc[C];
  for (int c = 0; c < C; ++c) xc[c] = _mm256_set1_ps(x[c]);
  for (; i + 8 <= n; i += 8) {
    __m256 acc = _mm256_loadu_ps(w + i);
    for (int c = 0; c < C; ++c) acc = _mm256_fnmadd_ps(widen(L[c] + i), xc[c], acc);
    _mm256_storeu_ps(w + i, acc);
  }
#endif
  for (; i < n; ++i) {
    float t = w[i];
    for (int c = 0; c < C; ++c) t -= half_to_float(L[c][i]) * x[c];
    w[i] = t;
  }
}

// Two accumulators per column (16 rows a round) so the C·2 FMA chains hide the FMA
// latency; the lanes are summed once at the end.
template <int C>
void dot_columns(int n, const uint16_t* const* L, const float* w, float* d) {
  int i = 0;
  for (int c = 0; c < C; ++c) d[c] = 0.0f;
#ifdef FE2_HALF_VECTORS
  __m256 a0[C], a1[C];
  for (int c = 0; c < C; ++c) a0[c] = a1[c] = _mm256_setzero_ps();
  for (; i + 16 <= n; i += 16) {
    const __m256 w0 = _mm256_loadu_ps(w + i), w1 = _mm256_loadu_ps(w + i + 8);
    for (int c = 0; c < C; ++c) {
      a0[c] = _mm256_fmadd_ps(widen(L[c] + i), w0, a0[c]);
      a1[c] = _mm256_fmadd_ps(widen(L[c] + i + 8), w1, a1[c]);
    }
  }
  for (; i + 8 <= n; i += 8) {
    const __m256 w0 = _mm256_loadu_ps(w + i);
    for (int c = 0; c < C; ++c) a0[c] = _mm256_fmadd_ps(widen(L[c] + i), w0, a0[c]);
  }
  for (int c = 0; c < C; ++c) d[c] = sum_lanes(_mm256_add_ps(a0[c], a1[c]));
#endif
  for (; i < n; ++i)
    for (int c = 0; c < C; ++c) d[c] += half_to_float(L[c][i]) * w[i];
}

/// body(std::integral_constant<int, ncols>) for ncols in [1, kMaxHalfColumns].
template <class Body>
void with_column_count(int ncols, Body body) {
  switch (ncols) {
    case 1: return body(std::integral_constant<int, 1>{});
    case 2: return body(std::integral_constant<int, 2>{});
    case 3: return body(std::integral_constant<int, 3>{});
    case 4: return body(std::integral_constant<int, 4>{});
    default: FE2_CHECK(false, "the binary16 kernels take 1 to {} columns, not {}", kMaxHalfColumns, ncols);
  }
}
static_assert(kMaxHalfColumns == 4, "with_column_count dispatches 1 to 4 columns");

}  // namespace

void subtract_half_columns(int ncols, int n, const uint16_t* const* columns, const float* x,
                           float* w) {
  with_column_count(ncols, [&](auto C) { subtract_columns<C()>(n, columns, x, w); });
}

void dot_half_columns(int ncols, int n, const uint16_t* const* columns, const float* w,
                      float* d) {
  with_column_count(ncols, [&](auto C) { dot_columns<C()>(n, columns, w, d); });
}

}  // namespace fe2
