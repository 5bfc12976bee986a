// Two doubles in one vector register (GCC/Clang vector extensions: SSE2 on x86-64, NEON on ARM,
// plain doubles elsewhere), for the six legs two at a time. Each lane does exactly the scalar
// arithmetic, in the same order (the forward sources are compiled with -ffp-contract=off, so no
// target fuses a multiply-add in one and not the other), so the results are those of the scalar
// loops bit for bit.
#pragma once

#include <cmath>
#include <cstring>

namespace stewart {

typedef double Pair __attribute__((vector_size(16)));
typedef long long PairBits __attribute__((vector_size(16)));  // a comparison's lanes: 0 or -1

// Lanes a[0], a[1] (unaligned).
inline Pair load_pair(const double *a) {
    Pair v;
    std::memcpy(&v, a, sizeof v);
    return v;
}
inline void store_pair(double *a, Pair v) { std::memcpy(a, &v, sizeof v); }
// Component i of the 3 x n column-major points k and k + 1.
inline Pair point_pair(const double *points, int i, int k) {
    return Pair{points[3 * k + i], points[3 * k + 3 + i]};
}
inline Pair sqrt_pair(Pair v) { return Pair{std::sqrt(v[0]), std::sqrt(v[1])}; }
inline Pair abs_pair(Pair v) {
    const PairBits magnitude = {0x7fffffffffffffffLL, 0x7fffffffffffffffLL};  // sign bit cleared
    return reinterpret_cast<Pair>(reinterpret_cast<PairBits>(v) & magnitude);
}
// True if any lane of a comparison is true.
inline bool any(PairBits m) { return (m[0] | m[1]) != 0; }

}  // namespace stewart
