// The four-pose kernel of closed_form_quad_avx2.cpp compiled also with AVX-512F, VL and DQ
// (csrc/CMakeLists.txt), still on 4-double vectors: the same operations in the same order (the
// same bits), but 32 vector registers instead of 16, so the values of a block spill less to the
// stack. Called only after a run-time check of the CPU (closed_form_batch.cpp).
#define STEWART_QUAD_KERNEL closed_form_quad_avx512vl
#define STEWART_QUAD_RUN closed_form_quad_avx512vl_run
#define STEWART_QUAD_WIDTH 4
#include "kinematics/closed_form_quad_kernel.inc"
