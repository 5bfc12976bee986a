// One linear filter of the classical washout, y = s^m / D(s) u with D monic of order n <= 3, in
// companion form (z, z', ..., z^(n-1)), discretised exactly for a zero-order-hold input.
#pragma once

namespace stewart {
namespace cueing {

constexpr int kMaxOrder = 3;

// D(s) = s^n + a[n-1] s^(n-1) + ... + a[0]; the output is z^(m), m <= n - 1 so that its first
// two derivatives are states or the input's feedthrough.
struct FilterDesign {
    int n = 1, m = 0;
    double a[kMaxOrder] = {0, 0, 0};
};

// x_{k+1} = Ad x_k + Bd u_k over a step dt with u held (the matrix exponential of the augmented
// matrix [[A, B], [0, 0]] dt).
struct FilterStep {
    double Ad[kMaxOrder][kMaxOrder] = {};
    double Bd[kMaxOrder] = {};
};

// Ad and Bd of design over dt > 0 (fixed-size arithmetic: no allocation).
void discretise(const FilterDesign &design, double dt, FilterStep &step);

// z advanced by one step with u held.
void advance(const FilterDesign &design, const FilterStep &step, double u, double z[kMaxOrder]);

// The output and its first two time derivatives at state z with input u (held: u' = 0).
void output(const FilterDesign &design, const double z[kMaxOrder], double u, double y[3]);

}  // namespace cueing
}  // namespace stewart
