// Row-major LU with partial pivoting on a block with extra (carried) columns, and its solves.
// Shared by the group blocks and the border system of the block solver.
#pragma once

namespace mbs {

// Factorises the first n columns of the m x width row-major block a (m >= n): P a = L [U W; 0 S].
// Multipliers are stored below the diagonal; rows n..m-1 of columns n.. hold S. False if a pivot
// is tiny.
bool lu_factor(double *a, int m, int n, int width, int *pivot);
// t (m values) <- L^-1 P t.
void lu_forward(const double *a, int m, int n, int width, const int *pivot, double *t);
// x (n values) <- U^-1 (t - W y), y the carried unknowns (width - n of them, may be null).
void lu_backward(const double *a, int n, int width, const double *t, const double *y, double *x);
// mu_top (n values) <- U^-T g.
void lu_forward_transposed(const double *a, int n, int width, const double *g, double *mu);
// t (m values, mu) <- P^T L^-T t.
void lu_backward_transposed(const double *a, int m, int n, int width, const int *pivot, double *t);

// lu_factor(a, N, N, N, pivot) with the size known when compiling (instantiated for N = 7).
template <int N>
bool lu_factor_square(double *a, int *pivot);
// mu <- (P^T L U)^-T g, lu_forward_transposed then lu_backward_transposed, for N x N (N = 7).
template <int N>
void lu_solve_transposed_square(const double *a, const int *pivot, const double *g, double *mu);

}  // namespace mbs
