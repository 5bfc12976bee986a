// The lane kernels (lane_lu_kernel.inc) with 8 lanes in two AVX2 registers, compiled with -mavx2
// (chosen at run time: six legs in one pass instead of two of four).
#define MBS_LANES 8
#define MBS_LANE_REGISTERS 2
#define MBS_LANE_KERNELS kLaneKernelsAvx2x2
#define MBS_LANE_KERNEL_NAME "8 lanes (avx2, two registers)"
#define MBS_LANE_NAMESPACE lanes8x2
#include "core/lane_lu_kernel.inc"
