#pragma once
// Internal helper of the fluid kernels: pairs of doubles with GCC/Clang vector extensions (SSE2 on
// x86-64, NEON on ARM, plain scalar code elsewhere). Every operation is element-wise IEEE
// arithmetic, so results are the same bits as the scalar formulas whatever the vector width;
// reductions keep a fixed number of partial results combined in a fixed order (deterministic).
#include <cstddef>

namespace jellysim::fluid::simd {

using Double2 = double __attribute__((vector_size(16)));
using Int2 = int __attribute__((vector_size(8)));

inline Double2 load2(const double* p) {
  Double2 v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
inline void store2(double* p, Double2 v) { __builtin_memcpy(p, &v, sizeof v); }
inline Double2 abs2(Double2 x) { return x < 0.0 ? -x : x; }
/// max(m, x) per lane (NaN is not reliably propagated: callers that care test for it apart).
inline Double2 max2(Double2 m, Double2 x) { return m > x ? m : x; }
inline Double2 min2(Double2 m, Double2 x) { return m < x ? m : x; }

/// Sum with four partial sums (two lanes × two accumulators), combined in a fixed order.
struct Sum4 {
  Double2 a{0.0, 0.0}, b{0.0, 0.0};
  double total() const { return (a[0] + a[1]) + (b[0] + b[1]); }
};
/// Maximum with four partial maxima (all ≥ 0 for absolute values).
struct Max4 {
  Double2 a{0.0, 0.0}, b{0.0, 0.0};
  double total() const {
    const Double2 m = max2(a, b);
    return m[0] > m[1] ? m[0] : m[1];
  }
};

/// Calls quad(i) for i = i0, i0 + 4, … while four elements remain, then pair(i) for a remaining
/// pair and one(i) for a last single element. quad adds into the accumulators `a` and `b` of
/// its reductions (two pairs), pair and one into `a` (one into lane 0).
template <class Quad, class Pair, class One>
inline void for_quads(int i0, int i1, Quad&& quad, Pair&& pair, One&& one) {
  int i = i0;
  for (; i + 4 <= i1; i += 4) quad(i);
  if (i + 2 <= i1) {
    pair(i);
    i += 2;
  }
  if (i < i1) one(i);
}

}  // namespace jellysim::fluid::simd
