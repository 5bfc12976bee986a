#include "core/lane_lu.hpp"

namespace mbs {

int runnable_lane_kernels(const LaneKernels *out[kMaxLaneKernels]) {
    int count = 0;
#if defined(__x86_64__) || defined(__i386__)
    __builtin_cpu_init();
#ifdef MBS_HAVE_AVX2X2_LANES
    if (__builtin_cpu_supports("avx2")) out[count++] = &kLaneKernelsAvx2x2;
#endif
#ifdef MBS_HAVE_AVX2_LANES
    if (__builtin_cpu_supports("avx2")) out[count++] = &kLaneKernelsAvx2;
#endif
#endif
    out[count++] = &kLaneKernelsPairs;
    return count;
}

const LaneKernels &lane_kernels_for(int family) {
    const LaneKernels *kernels[kMaxLaneKernels];
    const int count = runnable_lane_kernels(kernels);
    const LaneKernels *chosen = kernels[0];
    for (int k = 0; k < count; ++k)  // widest first: the last with room is the narrowest
        if (kernels[k]->lanes >= family && kernels[k]->lanes < chosen->lanes) chosen = kernels[k];
    return *chosen;
}

}  // namespace mbs
