// The closed-form levels of the inverse batch on the vector units: which kernel this CPU runs,
// and the model's constants in the kernel's layout.
#pragma once

#include "kinematics/closed_form.hpp"
#include "kinematics/closed_form_quad.hpp"
#include "stewart/stewart.h"

namespace stewart {

// The kernels: none (the scalar stewart_inverse_solve per row), portable, AVX2 with FMA, and the
// AVX2 kernel with AVX-512VL's 32 registers (same bits as avx2). Each later one is faster.
enum class VectorPath { scalar, portable, avx2, avx512vl };

// The fastest kernel this CPU runs (decided once, thread-safely; no state changes after).
VectorPath fastest_vector_path();

// The kernel stewart_inverse_batch runs at level fidelity: the fastest, but AVX2 rather than
// avx512vl at the massless level (there avx512vl takes 6 % fewer instructions and measured no
// faster, slower in 8 of 10 runs: the LU's chains of dependent operations bound it, not spills).
VectorPath batch_vector_path(int fidelity);

// False where a path is not built or the CPU lacks it (AVX2, AVX-512 off x86).
bool vector_path_available(VectorPath path);

// The kernel's constants for a batch at the kinematic or massless level of model pieces g
// (geometry), body, gravity, parameters p (strokes, length offsets) and options o.
QuadModel quad_model(const PlatformGeometry &g, const LumpedBody &body,
                     const Eigen::Vector3d &gravity, const stewart_params &p,
                     const stewart_inverse_options &o);

// closed_form_quad_portable, _avx2 or _avx512vl by path (not scalar).
unsigned closed_form_quad(VectorPath path, const QuadModel &m, const QuadRows &rows,
                          const stewart_inverse_batch_outputs &out, size_t row);
// closed_form_quad_portable_run, _avx2_run or _avx512vl_run by path (not scalar).
size_t closed_form_quad_run(VectorPath path, const QuadModel &m, const QuadRows &rows,
                            const stewart_inverse_batch_outputs &out, size_t row, size_t blocks,
                            unsigned &left);

}  // namespace stewart
