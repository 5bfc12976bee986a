// The four-pose kernel for any CPU (GCC vector extensions of two doubles: SSE2 on x86-64, NEON on
// AArch64, pairs of scalars elsewhere).
#define STEWART_QUAD_KERNEL closed_form_quad_portable
#define STEWART_QUAD_RUN closed_form_quad_portable_run
#define STEWART_QUAD_WIDTH 2
#include "kinematics/closed_form_quad_kernel.inc"
