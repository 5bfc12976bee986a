// The inverse batch on a chosen kernel (internal: the tests and bench-batch compare the paths;
// stewart_inverse_batch takes the fastest this CPU runs).
#pragma once

#include "kinematics/closed_form_batch.hpp"
#include "stewart/stewart_batch.h"

namespace stewart {

// stewart_inverse_batch with the kinematic and massless levels on path (VectorPath::scalar: one
// stewart_inverse_solve per row, as every level with tool or user frames and the full level).
// A path the CPU lacks runs as the portable one.
stewart_status inverse_batch(stewart_inverse *d, size_t n, const double *q, const double *q_dot,
                             const double *q_ddot, const stewart_inverse_batch_outputs *out,
                             stewart_batch_messages *messages, size_t *first_failed,
                             VectorPath path);

}  // namespace stewart
