// The closed-form levels (kinematic, massless) of four poses at once, one pose per lane of a
// 4-double vector: plain data in and out and no Eigen, because the kernel is compiled twice (once
// for AVX2 and FMA, once portable) and must share no inline code with the rest of the library.
#pragma once

#include <stddef.h>

#include "stewart/stewart_batch.h"

namespace stewart {

// What the kernel needs of a model and inverse options, copied once per batch.
struct QuadModel {
    // Per leg, each value four times over (a kernel loads one as a vector of lanes, the portable
    // one its first two): a_k (world) and b_k (platform frame), column k = leg k; the stroke
    // limits and the length offsets.
    alignas(32) double base[3][6][4], platform[3][6][4];
    alignas(32) double stroke_min[6][4], stroke_max[6][4], length_offset[6][4];
    double min_length;                               // PlatformGeometry::min_length [m]
    double characteristic_length;                    // scales the Jacobian's angular rows [m]
    double mass, com[3], inertia[3][3], gravity[3];  // the lumped platform (LumpedBody)
    double warn_condition, singular_condition;
    // The rows of J^T in the order partial pivoting gives them at the home pose (lu6_factor):
    // row r in place row_slot[r]. The kernel factors in that order without exchanges where its
    // pivots stay large enough.
    int row_slot[6];
    bool massless;  // else kinematic
};

// Four consecutive rows of a batch's inputs, 6 values each: q, and q_dot and q_ddot (NULL: 0).
struct QuadRows {
    const double *q, *q_dot, *q_ddot;
};

// Writes rows row..row + 3 of every column of out as stewart_inverse_solve would for the four
// poses, to rounding, status STEWART_OK (where out.status is not NULL), and returns the rows the
// scalar path must decide (and overwrite), bit l for row row + l: bad input (not finite, beyond
// 1e50, an angle beyond 1e4 rad, or near those limits), a failing row (a leg of no length, a
// singular Jacobian, a non-finite output) or one within rounding of a stroke limit or a condition
// threshold.
unsigned closed_form_quad_portable(const QuadModel &m, const QuadRows &rows,
                                   const stewart_inverse_batch_outputs &out, size_t row);
// The same on AVX2 and FMA (call only where the CPU has both).
unsigned closed_form_quad_avx2(const QuadModel &m, const QuadRows &rows,
                               const stewart_inverse_batch_outputs &out, size_t row);

// The same with AVX-512F, VL and DQ too (their 32 registers; call only where the CPU has all five).
unsigned closed_form_quad_avx512vl(const QuadModel &m, const QuadRows &rows,
                                   const stewart_inverse_batch_outputs &out, size_t row);

// closed_form_quad_portable on blocks (>= 1) of four rows in a row, rows row.. (rows: the first
// block's inputs), until a block leaves a row to the scalar path: returns the blocks written, and
// in left the mask of the last of them (0 where none leaves a row).
size_t closed_form_quad_portable_run(const QuadModel &m, const QuadRows &rows,
                                     const stewart_inverse_batch_outputs &out, size_t row,
                                     size_t blocks, unsigned &left);
// The same on AVX2 and FMA.
size_t closed_form_quad_avx2_run(const QuadModel &m, const QuadRows &rows,
                                 const stewart_inverse_batch_outputs &out, size_t row,
                                 size_t blocks, unsigned &left);
// The same with AVX-512F, VL and DQ too.
size_t closed_form_quad_avx512vl_run(const QuadModel &m, const QuadRows &rows,
                                     const stewart_inverse_batch_outputs &out, size_t row,
                                     size_t blocks, unsigned &left);

}  // namespace stewart
