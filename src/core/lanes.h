#pragma once
// Two doubles in one register (SSE2 on x86-64, NEON on AArch64, GCC's and Clang's vector
// extension elsewhere). Each lane gets the same IEEE operation as scalar code would, so
// a pair loop that evaluates two pairs at once gives the scalar loop's bits; only the
// square root and the division, which are slow on one lane, get twice the throughput.
#include <cmath>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#elif defined(__aarch64__)
#include <arm_neon.h>
#endif

namespace sluice {

using Double2 = double __attribute__((vector_size(16)));
using Mask2 = std::int64_t __attribute__((vector_size(16)));  // a comparison's lanes: all ones or zero

inline Double2 lanes(double a, double b) { return Double2{a, b}; }
inline Double2 splat(double a) { return Double2{a, a}; }

inline Double2 sqrt_lanes(Double2 v) {
#if defined(__SSE2__)
  return _mm_sqrt_pd(v);
#elif defined(__aarch64__)
  return vsqrtq_f64(v);
#else
  return Double2{std::sqrt(v[0]), std::sqrt(v[1])};
#endif
}

// Two consecutive doubles (an unaligned load: a Vec2's x and y).
inline Double2 load_lanes(const double* p) {
#if defined(__SSE2__)
  return _mm_loadu_pd(p);
#else
  return Double2{p[0], p[1]};
#endif
}

// Two consecutive floats widened to doubles (a Vec2f's x and y): exact, as a scalar cast.
inline Double2 widen_lanes(const float* p) {
#if defined(__SSE2__)
  // _mm_loadl_epi64 reads through a may_alias type: 8 bytes of floats, no aliasing breach.
  return _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p))));
#else
  return Double2{p[0], p[1]};
#endif
}

// a[0] * b[0] + a[1] * b[1], the products added x then y: the bits of a scalar 2D dot.
inline double dot_lanes(Double2 a, Double2 b) {
  const Double2 p = a * b;
  return p[0] + p[1];
}

// Per lane, m ? a : b, through masks (never a branch).
inline Double2 select_lanes(Mask2 m, Double2 a, Double2 b) {
  return reinterpret_cast<Double2>((reinterpret_cast<Mask2>(a) & m) | (reinterpret_cast<Mask2>(b) & ~m));
}

}  // namespace sluice
