// The lane kernels (lane_lu_kernel.inc) with 2 lanes: the portable vector extension, for every CPU.
#define MBS_LANES 2
#define MBS_LANE_KERNELS kLaneKernelsPairs
#define MBS_LANE_KERNEL_NAME "2 lanes (portable)"
#define MBS_LANE_NAMESPACE lanes2
#include "core/lane_lu_kernel.inc"
