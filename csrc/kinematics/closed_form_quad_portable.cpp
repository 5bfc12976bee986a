// The four-pose kernel for any CPU (GCC vector extensions, lowered to what the target has).
#define STEWART_QUAD_KERNEL closed_form_quad_portable
#include "kinematics/closed_form_quad_kernel.inc"
