#include "core/sparse_lu.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <utility>

namespace mbs {

namespace {
constexpr double kThreshold = 0.1;          // pivot choice: within 10 % of the column maximum
constexpr double kRuntimeThreshold = 1e-3;  // refactorisation: give up below 0.1 %

typedef double Pair __attribute__((vector_size(16)));

// Where the pairs of [c0, c1) end: c0 + an even count (c0 if the range is empty).
int pairs_end(int c0, int c1) { return c1 > c0 ? c0 + (c1 - c0) / 2 * 2 : c0; }

// y[c] -= a x[c] for c in [c0, ce) two at a time, then at ce if `single`: the spans are short
// (3 to 9 here), where the compiler's own vector loop spends more on its alias checks and
// remainders than on the arithmetic, and the program knows where the pairs end. Each element is
// the same product and difference as the scalar loop's.
inline void subtract_multiple_planned(double *__restrict y, const double *__restrict x, double a,
                                      int c0, int ce, bool single) {
    const Pair a2 = {a, a};
    for (int c = c0; c < ce; c += 2) {
        Pair yc, xc;
        std::memcpy(&yc, y + c, sizeof yc);
        std::memcpy(&xc, x + c, sizeof xc);
        yc -= a2 * xc;
        std::memcpy(y + c, &yc, sizeof yc);
    }
    if (single) y[ce] -= a * x[ce];
}
}  // namespace

bool same_program(const EliminationProgram &p, const EliminationProgram &q) {
    return p.m == q.m && p.n == q.n && p.width == q.width && p.below_start == q.below_start &&
           p.below == q.below && p.below_at == q.below_at && p.below_row == q.below_row &&
           p.span_begin == q.span_begin && p.span_end == q.span_end && p.own_end == q.own_end &&
           p.carried_begin == q.carried_begin && p.pair_end == q.pair_end &&
           p.own_pair_end == q.own_pair_end && p.carried_pair_end == q.carried_pair_end;
}

std::vector<int> choose_pivot_order(std::vector<double> &a, std::vector<char> &nz, int m, int n,
                                    int width, EliminationProgram &p) {
    std::vector<std::vector<double>> samples(1);
    samples[0].swap(a);
    std::vector<int> order = choose_common_pivot_order(samples, nz, m, n, width, p);
    a.swap(samples[0]);
    return order;
}

namespace {

// The pivot row of column k (rows k..m-1) by threshold Markowitz: among the pivots acceptable in
// every sample (within kThreshold of the column's maximum), the row with the fewest nonzeros; -1
// if there is none or a column is zero in a sample.
int markowitz_pivot(const std::vector<std::vector<double>> &samples, const std::vector<char> &nz,
                    int k, int m, int width, std::vector<double> &column_max) {
    for (size_t s = 0; s < samples.size(); ++s) {
        column_max[s] = 0;
        for (int i = k; i < m; ++i)
            column_max[s] = std::fmax(column_max[s], std::fabs(samples[s][i * width + k]));
        if (!(column_max[s] > 0)) return -1;
    }
    int best = -1, best_count = 0;
    double best_ratio = 0;
    for (int i = k; i < m; ++i) {
        double ratio = INFINITY;  // the smallest over the samples of |a(i, k)| / column max
        for (size_t s = 0; s < samples.size(); ++s)
            ratio = std::fmin(ratio, std::fabs(samples[s][i * width + k]) / column_max[s]);
        if (!(ratio >= kThreshold)) continue;
        int count = 0;
        for (int c = k; c < width; ++c) count += nz[i * width + c];
        // Ties of a common order go to the pivot largest against its column in every sample.
        const bool better = best < 0 || count < best_count ||
                            (samples.size() > 1 && count == best_count && ratio > best_ratio);
        if (better) best = i, best_count = count, best_ratio = ratio;
    }
    return best;
}

// Pivot k's step of the program (its row's columns right of it, the rows below it that it
// eliminates), and the elimination itself in every sample and in the nonzero pattern.
void eliminate_column(std::vector<std::vector<double>> &samples, std::vector<char> &nz,
                      const std::vector<int> &order, int k, int m, int width,
                      EliminationProgram &p) {
    p.below_start.push_back(static_cast<int>(p.below.size()));
    p.right_start.push_back(static_cast<int>(p.right.size()));
    for (int c = k + 1; c < width; ++c)
        if (nz[k * width + c]) p.right.push_back(c);
    for (int i = k + 1; i < m; ++i) {
        if (!nz[i * width + k]) continue;
        p.below.push_back(order[i]);  // by identity: later swaps move rows
        for (std::vector<double> &a : samples) {
            const double l = a[i * width + k] / a[k * width + k];
            a[i * width + k] = l;
            for (int t = p.right_start[k]; t < static_cast<int>(p.right.size()); ++t) {
                const int c = p.right[t];
                a[i * width + c] -= l * a[k * width + c];
            }
        }
        for (int t = p.right_start[k]; t < static_cast<int>(p.right.size()); ++t)
            nz[i * width + p.right[t]] = 1;
    }
}

// The program's spans and row positions, from its pivots' lists and the final row order.
void finish_program(const std::vector<int> &order, int m, int n, int width, EliminationProgram &p) {
    p.below_start.push_back(static_cast<int>(p.below.size()));
    p.right_start.push_back(static_cast<int>(p.right.size()));
    // Columns were pushed in increasing order: the carried ones close each pivot's list.
    for (int k = 0; k < n; ++k) {
        int s = p.right_start[k];
        while (s < p.right_start[k + 1] && p.right[s] < n) ++s;
        p.right_carried.push_back(s);
        const bool any = p.right_start[k] < p.right_start[k + 1];
        p.span_begin.push_back(any ? p.right[p.right_start[k]] : k + 1);
        p.span_end.push_back(any ? p.right[p.right_start[k + 1] - 1] + 1 : k + 1);
        p.own_end.push_back(std::min(p.span_end[k], n));
        p.carried_begin.push_back(std::max(p.span_begin[k], n));
        p.pair_end.push_back(pairs_end(p.span_begin[k], p.span_end[k]));
        p.own_pair_end.push_back(pairs_end(p.span_begin[k], p.own_end[k]));
        p.carried_pair_end.push_back(pairs_end(p.carried_begin[k], p.span_end[k]));
    }
    std::vector<int> position(m);
    for (int r = 0; r < m; ++r) position[order[r]] = r;
    for (int &i : p.below) i = position[i];
    p.below_at.resize(p.below.size());
    for (int k = 0; k < n; ++k)
        for (int t = p.below_start[k]; t < p.below_start[k + 1]; ++t)
            p.below_at[t] = p.below[t] * width + k;
    p.below_row.resize(p.below.size());
    for (size_t t = 0; t < p.below.size(); ++t) p.below_row[t] = p.below[t] * width;
}

}  // namespace

std::vector<int> choose_common_pivot_order(std::vector<std::vector<double>> &samples,
                                           std::vector<char> &nz, int m, int n, int width,
                                           EliminationProgram &p) {
    std::vector<int> order(m);
    std::iota(order.begin(), order.end(), 0);
    p = EliminationProgram{};
    p.m = m, p.n = n, p.width = width;
    auto swap_rows = [&](int r, int s) {
        for (int c = 0; c < width; ++c) {
            for (std::vector<double> &a : samples) std::swap(a[r * width + c], a[s * width + c]);
            std::swap(nz[r * width + c], nz[s * width + c]);
        }
        std::swap(order[r], order[s]);
    };
    std::vector<double> column_max(samples.size());
    for (int k = 0; k < n; ++k) {
        const int best = markowitz_pivot(samples, nz, k, m, width, column_max);
        if (best < 0) return {};
        if (best != k) swap_rows(k, best);
        eliminate_column(samples, nz, order, k, m, width, p);
    }
    finish_program(order, m, n, width, p);
    return order;
}

bool lu_factor_static(double *a, const EliminationProgram &p, double *inv_diag) {
    const int w = p.width;
    const int *below_row = p.below_row.data(), *below_start = p.below_start.data();
    const int *span_begin = p.span_begin.data(), *pair_end = p.pair_end.data(),
              *span_end = p.span_end.data();
    // |pivot| >= threshold * |a(i, k)| for every i below is |l_i| <= 1 / threshold: checked on
    // the multipliers as they are made (a failed block is re-scattered by the caller).
    const double limit = 1.0 / kRuntimeThreshold;
    for (int k = 0; k < p.n; ++k) {
        const double *__restrict row_k = a + k * w;
        const double pivot = row_k[k];
        if (pivot == 0.0) return false;
        const double inv = 1.0 / pivot;
        inv_diag[k] = inv;
        // One update over [span_begin, span_end) per row, its bounds from the program.
        const int c0 = span_begin[k], ce = pair_end[k];
        const bool single = ce < span_end[k];
        double largest = 0;
        for (int t = below_start[k]; t < below_start[k + 1]; ++t) {
            double *__restrict row_i = a + below_row[t];
            const double l = row_i[k] * inv;
            row_i[k] = l;
            const double size = std::fabs(l);
            if (size > largest) largest = size;
            subtract_multiple_planned(row_i, row_k, l, c0, ce, single);
        }
        if (!(largest <= limit)) return false;
    }
    return true;
}

void lu_forward_static(const double *a, const EliminationProgram &p, double *t) {
    for (int k = 0; k < p.n; ++k) {
        const double tk = t[k];
        if (tk != 0.0)
            for (int s = p.below_start[k]; s < p.below_start[k + 1]; ++s)
                t[p.below[s]] -= a[p.below_at[s]] * tk;
    }
}

void lu_backward_static(const double *a, const EliminationProgram &p, const double *inv_diag,
                        const double *t, const double *y, double *x) {
    const int n = p.n;
    for (int k = n - 1; k >= 0; --k) {
        const double *row = a + k * p.width;
        double sum = t[k];
        const int c0 = p.span_begin[k], c1 = p.span_end[k];
        for (int c = c0; c < std::min(c1, n); ++c) sum -= row[c] * x[c];
        if (y)
            for (int c = std::max(c0, n); c < c1; ++c) sum -= row[c] * y[c - n];
        x[k] = sum * inv_diag[k];
    }
}

void lu_forward_transposed_static(const double *a, const EliminationProgram &p,
                                  const double *inv_diag, const double *g, double *mu,
                                  double *carried) {
    const int n = p.n, w = p.width;
    const int *span_begin = p.span_begin.data(), *own_end = p.own_end.data(),
              *own_pair_end = p.own_pair_end.data(), *carried_begin = p.carried_begin.data(),
              *carried_pair_end = p.carried_pair_end.data(), *span_end = p.span_end.data();
    for (int k = 0; k < n; ++k) mu[k] = g[k];
    for (int k = 0; k < n; ++k) {
        const double *__restrict row = a + k * w;
        const double mk = (mu[k] *= inv_diag[k]);
        subtract_multiple_planned(mu, row, mk, span_begin[k], own_pair_end[k],
                                  own_pair_end[k] < own_end[k]);
        subtract_multiple_planned(carried - n, row, mk, carried_begin[k], carried_pair_end[k],
                                  carried_pair_end[k] < span_end[k]);
    }
}

void lu_backward_transposed_static(const double *a, const EliminationProgram &p, double *t) {
    const int *below = p.below.data(), *below_at = p.below_at.data();
    for (int k = p.n - 1; k >= 0; --k) {
        double sum = t[k];
        for (int s = p.below_start[k]; s < p.below_start[k + 1]; ++s)
            sum -= a[below_at[s]] * t[below[s]];
        t[k] = sum;
    }
}

}  // namespace mbs
