#pragma once
// Four floats as one SIMD value (the GCC/Clang vector extension: SSE on x86-64, NEON on
// AArch64), for the few hot loops the compiler does not vectorise by itself: table lookups
// and the interleaving of x, y, z into points.
#include <cstring>

namespace binpick::reconstruction::detail {

typedef float Float4 __attribute__((vector_size(16)));

inline Float4 loadFloat4(const float* p) {
  Float4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline void storeFloat4(float* p, Float4 v) { std::memcpy(p, &v, sizeof v); }

// The first two floats of v.
inline void storeFloat2(float* p, Float4 v) { std::memcpy(p, &v, 2 * sizeof(float)); }

inline Float4 lerpFloat4(Float4 a, Float4 b, float w) { return a + w * (b - a); }

// Four points' coordinates as 12 consecutive floats x0 y0 z0 x1 y1 z1 ...
inline void storeInterleaved3(float* out, Float4 x, Float4 y, Float4 z) {
  const Float4 xy01 = __builtin_shufflevector(x, y, 0, 4, 1, 5);    // x0 y0 x1 y1
  const Float4 xy23 = __builtin_shufflevector(x, y, 2, 6, 3, 7);    // x2 y2 x3 y3
  const Float4 yz1 = __builtin_shufflevector(xy01, z, 3, 5, 3, 5);  // y1 z1 . .
  storeFloat4(out, __builtin_shufflevector(xy01, z, 0, 1, 4, 2));
  storeFloat4(out + 4, __builtin_shufflevector(yz1, xy23, 0, 1, 4, 5));
  storeFloat4(out + 8, __builtin_shufflevector(xy23, z, 6, 2, 3, 7));
}

}  // namespace binpick::reconstruction::detail
