// The static LU of sparse_lu.hpp run on several group blocks at once, one block per vector lane:
// groups with the same elimination program (the legs of a hexapod) are stored interleaved, entry
// e of lane l at e * lanes + l, and every step of the program is one vector operation for all of
// them. Each lane does the scalar code's operations in its order (the core is compiled without
// fused multiply-add contraction), so every lane's results are the scalar path's, bit for bit.
//
// Kernels are built for 2 lanes (GCC's portable vector extension: SSE2 on every x86-64, NEON on
// AArch64), 4 (AVX2) and 8 in two AVX2 registers (lane_register_pair.hpp); `lane_kernels_for`
// picks for a plan the narrowest that takes its largest set in one pass, else the widest this CPU
// runs. (An 8-lane AVX-512F kernel was built and measured: on the one AVX-512 host at hand, a Zen
// 5, it was 15 % slower than two AVX2 registers, its gathers and masks dearer: not kept.)
#pragma once

#include "core/sparse_lu.hpp"

namespace mbs {

struct LaneKernels {
    const char *name;
    int lanes;
    // Zeroes the fill (a + fill[f], each lanes wide), gathers values[gather[e * lanes + l]] into
    // lane l at a + entries[e], then factors every lane in place; returns a bit per lane whose
    // factorisation the scalar lu_factor_static would have refused (a zero or a refused pivot).
    unsigned (*factor)(double *a, const EliminationProgram &p, double *inv_diag,
                       const double *values, const long *entries, const int *gather, int count,
                       const long *fill, int fill_count);
    // t <- L^-1 t (m values per lane).
    void (*forward)(const double *a, const EliminationProgram &p, double *t);
    // x <- U^-1 (t - W y), y shared by every lane (the border's unknowns).
    void (*backward)(const double *a, const EliminationProgram &p, const double *inv_diag,
                     const double *t, const double *y, double *x);
    // mu <- U^-T mu (n values per lane); carried <- -W^T mu (width - n values per lane, from
    // zero: the caller adds each lane's to the shared border, group by group).
    void (*forward_transposed)(const double *a, const EliminationProgram &p, const double *inv_diag,
                               double *mu, double *carried);
    // t <- L^-T t (m values per lane).
    void (*backward_transposed)(const double *a, const EliminationProgram &p, double *t);
};

extern const LaneKernels kLaneKernelsPairs;
#ifdef MBS_HAVE_AVX2_LANES
extern const LaneKernels kLaneKernelsAvx2;
#endif
#ifdef MBS_HAVE_AVX2X2_LANES
extern const LaneKernels kLaneKernelsAvx2x2;
#endif

// Every kernel built and runnable here, widest first (tests compare them all); returns the count.
constexpr int kMaxLaneKernels = 3;
int runnable_lane_kernels(const LaneKernels *out[kMaxLaneKernels]);
// For groups whose largest family (groups of one program) has `family` members: the narrowest
// runnable kernel with room for them all, else the widest (chosen when a solver is made: no
// global state).
const LaneKernels &lane_kernels_for(int family);

}  // namespace mbs
