// LU of a group block with a pivot order fixed in advance (rows already in pivot order), running
// only over the structural nonzeros found when the order was chosen (the fill included): the
// "refactorisation" half of a sparse direct solver. The pivot order is chosen once by a threshold
// Markowitz rule on sample values; a factorisation whose pivot falls below the threshold reports
// failure so the caller can fall back to partial pivoting.
#pragma once

#include <vector>

namespace mbs {

struct EliminationProgram {
    int m = 0, n = 0, width = 0;
    std::vector<int> below_start, below;  // per pivot k: rows i > k with a structural a(i, k)
    std::vector<int> below_at;            // per entry of below: where a(i, k) is, i width + k
    std::vector<int> right_start, right;  // per pivot k: columns c > k with a structural a(k, c)
    std::vector<int> right_carried;       // per pivot k: where its carried columns (c >= n) start
    // Per pivot k: the columns from its first to its last structural one right of the pivot,
    // [span_begin, span_end) (empty if none). Row k holds zeros between its structural entries
    // (nothing is ever written there), so a dense update over the span does what the list does,
    // with no index loads and in vector registers.
    std::vector<int> span_begin, span_end;
    // Per pivot k: the span split at column n, [span_begin, own_end) and [carried_begin, span_end).
    std::vector<int> own_end, carried_begin;
    // Per pivot k: where the span's pairs end (span_begin + an even count); one single beyond it
    // if it is short of span_end.
    std::vector<int> pair_end;
    std::vector<int> own_pair_end, carried_pair_end;  // the same for the two parts of the split
    std::vector<int> below_row;  // per entry of below: where row i starts, i width
};

// True if p and q make the same steps, so that one runs for blocks of the other (lane_lu.hpp):
// every field the factor and solves read. right_start, right and right_carried are the
// planner's record only (the spans carry their use) and are left out.
bool same_program(const EliminationProgram &p, const EliminationProgram &q);

// Chooses the pivot order on the m x width row-major sample `a` (overwritten) with structure
// `nonzero` (overwritten with the fill), both in the current row order: returns the new order of
// the rows (a permutation of 0..m-1) and fills the program, or returns an empty vector if some
// column has no usable pivot.
std::vector<int> choose_pivot_order(std::vector<double> &a, std::vector<char> &nonzero, int m,
                                    int n, int width, EliminationProgram &program);
// The same for blocks of one structure (`nonzero`) with several samples: each pivot must pass the
// threshold in every sample, so that the blocks share one order and one program (lane_lu.hpp).
std::vector<int> choose_common_pivot_order(std::vector<std::vector<double>> &samples,
                                           std::vector<char> &nonzero, int m, int n, int width,
                                           EliminationProgram &program);

// In place on the block (rows in pivot order), with the reciprocal pivots in inv_diag (n values:
// the solves multiply, since a division chain would bound their speed). False if a pivot is below
// the threshold.
bool lu_factor_static(double *a, const EliminationProgram &p, double *inv_diag);
// t <- L^-1 t.
void lu_forward_static(const double *a, const EliminationProgram &p, double *t);
// x <- U^-1 (t - W y).
void lu_backward_static(const double *a, const EliminationProgram &p, const double *inv_diag,
                        const double *t, const double *y, double *x);
// mu <- U^-T g (n values); carried -= W^T mu (width - n values; the block solver starts it at
// zero and adds it to the border, as the lane kernels do).
void lu_forward_transposed_static(const double *a, const EliminationProgram &p,
                                  const double *inv_diag, const double *g, double *mu,
                                  double *carried);
// t <- L^-T t (m values).
void lu_backward_transposed_static(const double *a, const EliminationProgram &p, double *t);

}  // namespace mbs
