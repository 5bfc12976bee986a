// The lane kernels' vector and mask types (lane_lu_kernel.inc) as two registers of L / 2 lanes
// each: eight lanes where the widest registers hold four (AVX2). Every operation is the
// one-register operation on each half, so each lane computes what it would in one register, and
// GCC keeps the halves in registers (a 64-byte vector_size type on AVX2 it splits through memory).
// Included inside the kernel's namespace, with L defined.
#pragma once

static_assert(L % 2 == 0, "two registers of L / 2 lanes");
typedef double Half __attribute__((vector_size(L / 2 * sizeof(double))));
typedef decltype(Half{} == Half{}) HalfMask;

struct V {
    Half lo, hi;
};
struct Mask {
    HalfMask lo, hi;
};

// Each half loaded and stored on its own (a 64-byte memcpy goes through the stack).
inline Half load_half(const double *p) {
    Half h;
    std::memcpy(&h, p, sizeof h);
    return h;
}
inline V load(const double *p) { return {load_half(p), load_half(p + L / 2)}; }
inline void store(double *p, V v) {
    std::memcpy(p, &v.lo, sizeof v.lo);
    std::memcpy(p + L / 2, &v.hi, sizeof v.hi);
}

inline V operator+(V a, double s) { return {a.lo + s, a.hi + s}; }
inline V operator-(V a, V b) { return {a.lo - b.lo, a.hi - b.hi}; }
inline V operator*(V a, V b) { return {a.lo * b.lo, a.hi * b.hi}; }
inline V operator/(V a, V b) { return {a.lo / b.lo, a.hi / b.hi}; }
inline V &operator-=(V &a, V b) { return a = a - b; }
inline Mask operator==(V a, V b) { return {a.lo == b.lo, a.hi == b.hi}; }
inline Mask operator!=(V a, V b) { return {a.lo != b.lo, a.hi != b.hi}; }
inline Mask operator>(V a, V b) { return {a.lo > b.lo, a.hi > b.hi}; }
inline Mask operator<=(V a, V b) { return {a.lo <= b.lo, a.hi <= b.hi}; }
inline Mask operator~(Mask m) { return {~m.lo, ~m.hi}; }
inline Mask &operator|=(Mask &a, Mask b) { return a = Mask{a.lo | b.lo, a.hi | b.hi}; }

// a where the mask is set, else b.
inline V select(Mask m, V a, V b) { return {m.lo ? a.lo : b.lo, m.hi ? a.hi : b.hi}; }
// |v| by clearing the sign bit (and +0 for -0: the same verdicts as the scalar fabs).
inline V magnitude(V v) {
    const HalfMask no_sign = ~(HalfMask)(-Half{});
    return {(Half)((HalfMask)v.lo & no_sign), (Half)((HalfMask)v.hi & no_sign)};
}
// Whether lane l of a mask is set.
inline bool lane(Mask m, int l) { return (l < L / 2 ? m.lo[l] : m.hi[l - L / 2]) != 0; }
