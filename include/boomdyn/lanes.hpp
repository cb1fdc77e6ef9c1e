// Four doubles in one SIMD vector, for kernels that evaluate four work items
// at once, one item per lane (a beam's elements in a residual). GCC's vector
// extension: every operator acts lane by lane with IEEE double arithmetic,
// so a lane computes bit for bit what the same scalar code computes (no FMA
// in this build, no reassociation). An AVX register in the x86-64-v3 build,
// two SSE2 registers in the generic one.
#pragma once

#include <cstring>

#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace boomdyn::lanes {

constexpr int kWidth = 4;
using Lanes4 = double __attribute__((vector_size(kWidth * sizeof(double))));

// Unaligned load and store of four consecutive doubles.
inline Lanes4 load(const double *p)
{
  Lanes4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void store(double *p, const Lanes4 &v) { std::memcpy(p, &v, sizeof v); }

// out[i][j] = rows[j][offset + i] (i, j < 4): four entries of four items
// into lanes. Pure data movement.
inline void gatherLanes(const double *const rows[kWidth], int offset, Lanes4 out[kWidth])
{
#if defined(__AVX__)
  const __m256d r0 = _mm256_loadu_pd(rows[0] + offset), r1 = _mm256_loadu_pd(rows[1] + offset);
  const __m256d r2 = _mm256_loadu_pd(rows[2] + offset), r3 = _mm256_loadu_pd(rows[3] + offset);
  const __m256d t0 = _mm256_unpacklo_pd(r0, r1), t1 = _mm256_unpackhi_pd(r0, r1); // (0 0 2 2), (1 1 3 3) of rows 0, 1
  const __m256d t2 = _mm256_unpacklo_pd(r2, r3), t3 = _mm256_unpackhi_pd(r2, r3); // the same of rows 2, 3
  out[0] = _mm256_permute2f128_pd(t0, t2, 0x20);
  out[1] = _mm256_permute2f128_pd(t1, t3, 0x20);
  out[2] = _mm256_permute2f128_pd(t0, t2, 0x31);
  out[3] = _mm256_permute2f128_pd(t1, t3, 0x31);
#else
  for (int i = 0; i < kWidth; ++i)
    for (int j = 0; j < kWidth; ++j) out[i][j] = rows[j][offset + i];
#endif
}

// rows[j][offset + i] = in[i][j] (i, j < 4): lanes back to the items.
inline void scatterLanes(const Lanes4 in[kWidth], double *const rows[kWidth], int offset)
{
  Lanes4 t[kWidth];
  const double *src[kWidth] = {reinterpret_cast<const double *>(&in[0]), reinterpret_cast<const double *>(&in[1]),
                               reinterpret_cast<const double *>(&in[2]), reinterpret_cast<const double *>(&in[3])};
  gatherLanes(src, 0, t); // the transpose is its own inverse
  for (int j = 0; j < kWidth; ++j) store(rows[j] + offset, t[j]);
}

} // namespace boomdyn::lanes
