// The four-pose kernel compiled with -mavx2 -mfma (csrc/CMakeLists.txt): called only after a
// run-time check of the CPU (closed_form_batch.cpp).
#define STEWART_QUAD_KERNEL closed_form_quad_avx2
#define STEWART_QUAD_RUN closed_form_quad_avx2_run
#define STEWART_QUAD_WIDTH 4
#include "kinematics/closed_form_quad_kernel.inc"
