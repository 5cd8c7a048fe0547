#pragma once
// The gap update's first test, a block's row of 8 cells at a time in floats (GridIndex::
// lower_gaps in grid_index.cpp); here so that tests/index_test.cpp checks it against the exact
// test in double.

#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace dla {

namespace detail {

//! For a row of 8 cells' gaps (in gap units), a bit for each cell whose squared distance to a
//! new particle, yz2 + along[i] (in units², as floats), may lie below the square of its gap:
//! set for every cell the exact test in double would lower, as the floats' rounding (under
//! 2e-7 of the square) is covered by 1e-6. An update meets about 600 cells and lowers about
//! 16: most rows come back empty after a few instructions (GridIndex::lower_gaps).
inline unsigned may_lower_gaps(const std::uint8_t* row, float yz2, const float* along) {
  constexpr float kSlack = 1.000001f;  // the square of a gap, widened past the floats' rounding
#if defined(__SSE2__)
  const __m128i zero = _mm_setzero_si128();
  const __m128i gaps = _mm_unpacklo_epi8(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(row)), zero);
  const __m128 slack = _mm_set1_ps(kSlack), yz = _mm_set1_ps(yz2);
  unsigned bits = 0;
  for (int half = 0; half < 2; ++half) {
    const __m128 gap = _mm_cvtepi32_ps(half ? _mm_unpackhi_epi16(gaps, zero) : _mm_unpacklo_epi16(gaps, zero));
    const __m128 d2 = _mm_add_ps(yz, _mm_loadu_ps(along + 4 * half));
    bits |= static_cast<unsigned>(_mm_movemask_ps(_mm_cmplt_ps(d2, _mm_mul_ps(_mm_mul_ps(gap, gap), slack)))) << (4 * half);
  }
  return bits;
#else
  unsigned bits = 0;
  for (int i = 0; i < 8; ++i) {
    const float gap = row[i];
    bits |= static_cast<unsigned>(yz2 + along[i] < gap * gap * kSlack) << i;
  }
  return bits;
#endif
}

}  // namespace detail

}  // namespace dla
