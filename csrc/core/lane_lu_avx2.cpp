// The lane kernels (lane_lu_kernel.inc) with 4 lanes, compiled with -mavx2 (chosen at run time).
#define MBS_LANES 4
#define MBS_LANE_KERNELS kLaneKernelsAvx2
#define MBS_LANE_KERNEL_NAME "4 lanes (avx2)"
#define MBS_LANE_NAMESPACE lanes4
#include "core/lane_lu_kernel.inc"
