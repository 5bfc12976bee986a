// The lane kernels (lane_lu_kernel.inc) with 8 lanes, compiled with -mavx512f (chosen at run time).
#define MBS_LANES 8
#define MBS_LANE_KERNELS kLaneKernelsAvx512
#define MBS_LANE_KERNEL_NAME "8 lanes (avx512)"
#define MBS_LANE_NAMESPACE lanes8
#include "core/lane_lu_kernel.inc"
