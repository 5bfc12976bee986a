#include "core/lane_lu.hpp"

namespace mbs {

int runnable_lane_kernels(const LaneKernels *out[3]) {
    int count = 0;
#if defined(__x86_64__) || defined(__i386__)
    __builtin_cpu_init();
#ifdef MBS_HAVE_AVX512_LANES
    if (__builtin_cpu_supports("avx512f")) out[count++] = &kLaneKernelsAvx512;
#endif
#ifdef MBS_HAVE_AVX2_LANES
    if (__builtin_cpu_supports("avx2")) out[count++] = &kLaneKernelsAvx2;
#endif
#endif
    out[count++] = &kLaneKernelsPairs;
    return count;
}

const LaneKernels &lane_kernels_for_cpu() {
    const LaneKernels *kernels[3];
    runnable_lane_kernels(kernels);
    return *kernels[0];
}

}  // namespace mbs
