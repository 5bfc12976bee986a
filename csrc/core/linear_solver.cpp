#include "core/linear_solver.hpp"

#include <algorithm>
#include <cstring>
#include <utility>

#include "core/dense_lu.hpp"
#include "core/lane_lu.hpp"
#include "core/lane_sets.hpp"

namespace mbs {

namespace {

class DenseSolver final : public LinearSolver {
public:
    explicit DenseSolver(const Mechanism &m)
        : m_(m), n_(m.equations), a_(n_ * n_), pivot_(n_), work_(n_) {}
    bool factor(const double *values) override {
        std::fill(a_.begin(), a_.end(), 0.0);
        for (int t = 0; t < m_.values(); ++t)
            a_[m_.pattern_row[t] * n_ + m_.pattern_col[t]] = values[t];
        return lu_factor(a_.data(), n_, n_, n_, pivot_.data());
    }
    void solve(double *x) override {
        lu_forward(a_.data(), n_, n_, n_, pivot_.data(), x);
        std::copy(x, x + n_, work_.begin());
        lu_backward(a_.data(), n_, n_, work_.data(), nullptr, x);
    }
    void solve_transposed(double *x) override {
        std::copy(x, x + n_, work_.begin());
        lu_forward_transposed(a_.data(), n_, n_, work_.data(), x);
        lu_backward_transposed(a_.data(), n_, n_, n_, pivot_.data(), x);
    }
    const char *name() const override { return "dense LU"; }

private:
    const Mechanism &m_;
    int n_;
    std::vector<double> a_;
    std::vector<int> pivot_;
    std::vector<double> work_;
};

// to[i] = from[i] for i < n, two at a time.
typedef double Pair __attribute__((vector_size(16)));
inline void copy_pairs(double *__restrict to, const double *__restrict from, size_t n) {
    size_t i = 0;
    for (; i + 2 <= n; i += 2) {
        Pair v;
        std::memcpy(&v, from + i, sizeof v);
        std::memcpy(to + i, &v, sizeof v);
    }
    if (i < n) to[i] = from[i];
}

// y[i] -= c[i] a for i < n, two at a time: each element the scalar loop's product and difference.
inline void subtract_pairs(double *__restrict y, const double *__restrict c, double a, size_t n) {
    const Pair a2 = {a, a};
    size_t i = 0;
    for (; i + 2 <= n; i += 2) {
        Pair yi, ci;
        std::memcpy(&yi, y + i, sizeof yi);
        std::memcpy(&ci, c + i, sizeof ci);
        yi -= ci * a2;
        std::memcpy(y + i, &yi, sizeof yi);
    }
    if (i < n) y[i] -= c[i] * a;
}

// to[c] = from[cols[c]] for c < n, where cols is whole bodies' 7 neighbouring coordinates in a
// row (a group's columns, as find_groups lists them): body by body, unrolled.
inline void gather_bodies(double *__restrict to, const double *__restrict from, const int *cols,
                          int n) {
    static_assert(MBS_BODY_COORDINATES == 7, "a body's coordinates are three pairs and one value");
    for (int b = 0; b < n; b += MBS_BODY_COORDINATES) {
        const double *body = from + cols[b];
        copy_pairs(to + b, body, 6);
        to[b + 6] = body[6];
    }
}

// x[rows[r]] = t[r] for r < n, three per turn (the rows are in pivot order, not neighbours: the
// loop's own count and branch were as many instructions as the copies).
inline void scatter_rows(double *__restrict x, const double *__restrict t, const int *rows, int n) {
    int r = 0;
    for (; r + 3 <= n; r += 3) {
        x[rows[r]] = t[r];
        x[rows[r + 1]] = t[r + 1];
        x[rows[r + 2]] = t[r + 2];
    }
    for (; r < n; ++r) x[rows[r]] = t[r];
}

// The usual border: one hub body's coordinates (a platform), solved by the fixed-size LU.
constexpr int kOneHub = MBS_BODY_COORDINATES;

class BlockSolver final : public LinearSolver {
public:
    // kernels: the lane kernels for groups of the same shape, or null for one group at a time;
    // lanes: the lane sets planned for their width.
    BlockSolver(const Mechanism &m, const LaneKernels *kernels, LaneLayout lanes)
        : m_(m), p_(*m.block_plan), kernels_(kernels), lanes_(std::move(lanes)),
          lane_ws_(lanes_.workspace), lane_inv_(lanes_.pivots), lane_t_(lanes_.vectors),
          lane_x_(lanes_.vectors), lane_carried_(lanes_.carried), group_t_offset_(p_.groups.size()),
          ws_(p_.workspace), coupling_(p_.coupling_row.size()), pivot_(p_.pivots),
          inv_diag_(p_.pivots), border_pivot_(p_.border), rhs_(m.equations), group_t_(m.equations),
          border_(p_.border), border_work_(p_.border), group_x_(m.coordinates),
          coupling_fixed_row_(p_.coupling_row.size()), static_used_(p_.groups.size(), 0),
          dirty_(p_.groups.size(), 0), steps_(p_.groups.size()) {
        // Fixed coordinate -> its identity row, for the transposed solve.
        std::vector<int> row_of(m.coordinates, -1);
        for (size_t i = 0; i < p_.fixed_cols.size(); ++i)
            row_of[p_.fixed_cols[i]] = p_.fixed_rows[i];
        for (size_t k = 0; k < p_.coupling_col.size(); ++k)
            coupling_fixed_row_[k] = row_of[p_.coupling_col[k]];
        coupling_from_.resize(p_.coupling_row.size());
        // The blocks of groups in lane sets take their values by the sets' gathers (and by the
        // group's own list on a fallback), not by runs.
        std::vector<char> in_lanes(p_.workspace, 0);
        for (size_t gi = 0; gi < p_.groups.size(); ++gi) {
            const BlockGroup &g = p_.groups[gi];
            if (lanes_.set_of[gi] >= 0)
                std::fill(in_lanes.begin() + g.offset,
                          in_lanes.begin() + g.offset + g.rows.size() * (g.cols.size() + p_.border),
                          1);
        }
        int t_offset = 0;
        for (size_t gi = 0; gi < p_.groups.size(); ++gi) {
            group_t_offset_[gi] = t_offset;
            t_offset += static_cast<int>(p_.groups[gi].rows.size());
        }
        std::vector<int> run_from, run_to, run_length;
        for (int t = 0; t < m.values(); ++t) {
            const int d =
                p_.value_dest[t] >= 0 && in_lanes[p_.value_dest[t]] ? -1 : p_.value_dest[t];
            // Values go as runs: a joint's row of one body's 7 values lands on 7 neighbouring
            // places of its block. Identically zero values (e.g. in an identity) ride along: a
            // zero lands where the block holds a zero already.
            if (d >= 0) {
                const bool extends = !run_from.empty() &&
                                     run_from.back() + run_length.back() == t &&
                                     run_to.back() + run_length.back() == d;
                if (extends) {
                    ++run_length.back();
                } else {
                    run_from.push_back(t), run_to.push_back(d), run_length.push_back(1);
                }
            }
            if (d <= -2) coupling_from_[-2 - d] = t;
        }
        // The common run, a body's whole row, goes to a list of its own, copied without lengths.
        for (size_t r = 0; r < run_from.size(); ++r)
            if (run_length[r] == MBS_BODY_COORDINATES)
                row_from_.push_back(run_from[r]), row_to_.push_back(run_to[r]);
            else
                other_from_.push_back(run_from[r]), other_to_.push_back(run_to[r]),
                    other_length_.push_back(run_length[r]);
        // Coupling values as runs too: a joint's row of a fixed body is neighbouring values, one
        // equation, neighbouring identity rows (k is in value order, so runs are in k order).
        for (size_t k = 0; k < coupling_from_.size(); ++k) {
            const size_t s = coupling_start_.empty() ? 0 : coupling_start_.back();
            const size_t n = k - s;
            const int step = static_cast<int>(n);
            const bool extends = !coupling_start_.empty() &&
                                 coupling_from_[k] == coupling_from_[s] + step &&
                                 p_.coupling_row[k] == p_.coupling_row[s] &&
                                 coupling_fixed_row_[k] == coupling_fixed_row_[s] + step;
            if (!extends) coupling_start_.push_back(k);
        }
        coupling_start_.push_back(coupling_from_.size());
    }

    // Not copied: steps_ point into its own vectors.
    BlockSolver(const BlockSolver &) = delete;
    BlockSolver &operator=(const BlockSolver &) = delete;

    bool factor(const double *values) override {
        clear_blocks();
        copy_values(values);
        factor_lane_sets(values);
        bool fell_back = false;
        if (!factor_groups(values, fell_back)) {
            steps_stale_ = true;
            return false;
        }
        // The steps change only with a fallback, this time or the time before.
        if (fell_back || steps_stale_) choose_steps();
        steps_stale_ = fell_back;
        const int nb = p_.border;
        double *border = ws_.data() + p_.border_offset;
        if (nb == kOneHub) return lu_factor_square<kOneHub>(border, border_pivot_.data());
        return lu_factor(border, nb, nb, nb, border_pivot_.data());
    }

    void solve(double *x) override {
        std::copy(x, x + m_.equations, rhs_.begin());
        bool fixed_move = false;  // fixed bodies usually stay put: then the coupling adds nothing
        for (size_t i = 0; i < p_.fixed_cols.size(); ++i) {
            x[p_.fixed_cols[i]] = rhs_[p_.fixed_rows[i]];
            fixed_move = fixed_move || rhs_[p_.fixed_rows[i]] != 0.0;
        }
        if (fixed_move)
            for (size_t k = 0; k < coupling_.size(); ++k)
                rhs_[p_.coupling_row[k]] -= coupling_[k] * x[p_.coupling_col[k]];
        const int nb = p_.border, L = lanes_.lanes;
        for (const LaneSet &s : lanes_.sets) {
            double *t = lane_t_.data() + s.vectors;
            const int *row_of = s.row_of.data();
            for (int i = 0; i < s.mg * L; ++i) t[i] = rhs_[row_of[i]];
            kernels_->forward(lane_ws_.data() + s.offset, s.lead->program, t);
        }
        for (const BlockGroup &g : p_.groups) {
            const int mg = static_cast<int>(g.rows.size()), ng = static_cast<int>(g.cols.size());
            const GroupStep &step = steps_[&g - p_.groups.data()];
            if (step.path != kLane) {
                double *t = step.t;
                for (int r = 0; r < mg; ++r) t[r] = rhs_[g.rows[r]];
                if (step.path == kStatic) lu_forward_static(ws_.data() + g.offset, g.program, t);
                else
                    lu_forward(ws_.data() + g.offset, mg, ng, ng + nb,
                               pivot_.data() + g.pivot_offset, t);
            }
            for (int r = ng; r < mg; ++r)
                border_[g.first_leftover + r - ng] = step.t[r * step.stride];
        }
        const int leftover = nb - static_cast<int>(p_.border_rows.size());
        for (size_t r = 0; r < p_.border_rows.size(); ++r)
            border_[leftover + r] = rhs_[p_.border_rows[r]];
        const double *s = ws_.data() + p_.border_offset;
        lu_forward(s, nb, nb, nb, border_pivot_.data(), border_.data());
        lu_backward(s, nb, nb, border_.data(), nullptr, border_work_.data());
        for (int c = 0; c < nb; ++c) x[p_.border_cols[c]] = border_work_[c];
        for (const LaneSet &set : lanes_.sets) {
            double *xs = lane_x_.data() + set.vectors;
            kernels_->backward(lane_ws_.data() + set.offset, set.lead->program,
                               lane_inv_.data() + set.pivots, lane_t_.data() + set.vectors,
                               border_work_.data(), xs);
            for (size_t l = 0; l < set.groups.size(); ++l) {
                if (!static_used_[set.groups[l]]) continue;
                const std::vector<int> &cols = p_.groups[set.groups[l]].cols;
                for (int c = 0; c < set.ng; ++c) x[cols[c]] = xs[c * L + l];
            }
        }
        for (const BlockGroup &g : p_.groups) {
            const int ng = static_cast<int>(g.cols.size());
            const GroupStep &step = steps_[&g - p_.groups.data()];
            if (step.path == kLane) continue;
            const double *t = step.t;
            if (step.path == kStatic)
                lu_backward_static(ws_.data() + g.offset, g.program,
                                   inv_diag_.data() + g.pivot_offset, t, border_work_.data(),
                                   group_x_.data());
            else
                lu_backward(ws_.data() + g.offset, ng, ng + nb, t, border_work_.data(),
                            group_x_.data());
            for (int c = 0; c < ng; ++c) x[g.cols[c]] = group_x_[c];
        }
    }

    void solve_transposed(double *x) override {
        std::copy(x, x + m_.coordinates, rhs_.begin());  // g, coordinate order
        reduce_transposed_to_border();
        const int nb = p_.border;
        const double *s = ws_.data() + p_.border_offset;
        if (nb == kOneHub) {
            lu_solve_transposed_square<kOneHub>(s, border_pivot_.data(), border_.data(),
                                                border_work_.data());
        } else {
            lu_forward_transposed(s, nb, nb, border_.data(), border_work_.data());
            lu_backward_transposed(s, nb, nb, nb, border_pivot_.data(), border_work_.data());
        }
        back_substitute_transposed(x);
    }

    const char *name() const override { return "bordered block LU"; }
    long fallbacks() const override { return fallbacks_; }

private:
    // solve_transposed's stages. The groups' forward substitutions (lanes, programs, pivoted),
    // each group's -W^T mu reduced into the border's right-hand side border_.
    void reduce_transposed_to_border() {
        const int nb = p_.border, L = lanes_.lanes;
        for (int c = 0; c < nb; ++c) border_[c] = rhs_[p_.border_cols[c]];
        for (const LaneSet &s : lanes_.sets) {
            double *mu = lane_t_.data() + s.vectors;
            const int *col_of = s.col_of.data();
            for (int i = 0; i < s.ng * L; ++i) mu[i] = rhs_[col_of[i]];
            kernels_->forward_transposed(lane_ws_.data() + s.offset, s.lead->program,
                                         lane_inv_.data() + s.pivots, mu,
                                         lane_carried_.data() + s.carried);
        }
        // Each group's -W^T mu, from zero, added to the border in group order from where its
        // step has it: the lanes make theirs side by side, one group at a time the same sums.
        for (const BlockGroup &g : p_.groups) {
            const int ng = static_cast<int>(g.cols.size());
            const GroupStep &step = steps_[&g - p_.groups.data()];
            const double *a = ws_.data() + g.offset;
            if (step.path != kLane) gather_bodies(group_x_.data(), rhs_.data(), g.cols.data(), ng);
            if (step.path == kPivoted) {  // straight into the border, as partial pivoting does
                lu_forward_transposed(a, ng, ng + nb, group_x_.data(), step.t);
                for (int k = 0; k < ng; ++k) {
                    const double mu = step.t[k];
                    const double *w = a + k * (ng + nb) + ng;
                    for (int b = 0; b < nb; ++b) border_[b] -= w[b] * mu;
                }
                continue;
            }
            if (step.path == kStatic) {
                std::fill(step.carried, step.carried + nb, 0.0);
                lu_forward_transposed_static(a, g.program, inv_diag_.data() + g.pivot_offset,
                                             group_x_.data(), step.t, step.carried);
            }
            for (int c = 0; c < nb; ++c) border_[c] += step.carried[c * step.stride];
        }
    }

    // From the border's solution (border_work_): every group's backward substitution into x,
    // then the border rows, the fixed bodies' rows and their coupling.
    void back_substitute_transposed(double *x) {
        const int nb = p_.border, L = lanes_.lanes;
        for (const LaneSet &set : lanes_.sets) {
            double *t = lane_t_.data() + set.vectors;
            for (int l = 0; l < L; ++l) {
                const int first = set.first_leftover[l] - set.ng;
                for (int r = set.ng; r < set.mg; ++r) t[r * L + l] = border_work_[first + r];
            }
            kernels_->backward_transposed(lane_ws_.data() + set.offset, set.lead->program, t);
            const int *row_of = set.row_of.data();
            for (size_t l = 0; l < set.groups.size(); ++l) {
                if (!static_used_[set.groups[l]]) continue;
                for (int i = static_cast<int>(l); i < set.mg * L; i += L) x[row_of[i]] = t[i];
            }
        }
        for (const BlockGroup &g : p_.groups) {
            const int mg = static_cast<int>(g.rows.size()), ng = static_cast<int>(g.cols.size());
            const GroupStep &step = steps_[&g - p_.groups.data()];
            if (step.path == kLane) continue;
            double *t = step.t;
            for (int r = ng; r < mg; ++r) t[r] = border_work_[g.first_leftover + r - ng];
            if (step.path == kStatic)
                lu_backward_transposed_static(ws_.data() + g.offset, g.program, t);
            else
                lu_backward_transposed(ws_.data() + g.offset, mg, ng, ng + nb,
                                       pivot_.data() + g.pivot_offset, t);
            scatter_rows(x, t, g.rows.data(), mg);
        }
        const int leftover = nb - static_cast<int>(p_.border_rows.size());
        for (size_t r = 0; r < p_.border_rows.size(); ++r)
            x[p_.border_rows[r]] = border_work_[leftover + r];
        for (size_t i = 0; i < p_.fixed_cols.size(); ++i)
            x[p_.fixed_rows[i]] = rhs_[p_.fixed_cols[i]];
        // Run by run in k order: each fixed row takes the same differences in the same order. A
        // fixed body's whole row, the common run, unrolled.
        const size_t *const start = coupling_start_.data();
        const int *const fixed_row = coupling_fixed_row_.data(), *const row =
                                                                     p_.coupling_row.data();
        const double *const coupling = coupling_.data();
        for (size_t r = 0; r + 1 < coupling_start_.size(); ++r) {
            const size_t k = start[r], n = start[r + 1] - k;
            double *to = x + fixed_row[k];
            const double mu = x[row[k]];
            if (n == MBS_BODY_COORDINATES) {
                subtract_pairs(to, coupling + k, mu, 6);
                to[6] -= coupling[k + 6] * mu;
            } else {
                subtract_pairs(to, coupling + k, mu, n);
            }
        }
    }

    // factor's stages. The blocks' workspace cleared: blocks factored by their program keep zeros
    // wherever the program does not write, so only the fill needs clearing; others (and the
    // border system) are cleared whole.
    void clear_blocks() {
        for (size_t gi = 0; gi < p_.groups.size(); ++gi) {
            const BlockGroup &g = p_.groups[gi];
            if (lanes_.set_of[gi] >= 0) continue;  // its block is written on a fallback only
            if (g.has_program && !dirty_[gi]) {
                for (int f : g.fill) ws_[f] = 0.0;
            } else {
                const size_t size = g.rows.size() * (g.cols.size() + p_.border);
                std::fill(ws_.begin() + g.offset, ws_.begin() + g.offset + size, 0.0);
                dirty_[gi] = 0;
            }
        }
        std::fill(ws_.begin() + p_.border_offset, ws_.end(), 0.0);
    }

    // The Jacobian's values into the blocks' rows, the other runs and the fixed bodies' coupling.
    void copy_values(const double *values) {
        // Typed copies through local pointers: a memcpy's stores may alias anything, and made
        // the compiler reload every vector's data pointer per run.
        double *const ws = ws_.data();
        const int *const row_from = row_from_.data(), *const row_to = row_to_.data();
        const size_t rows = row_from_.size();
        static_assert(MBS_BODY_COORDINATES == 7, "a body's row is three pairs and one value");
        const auto copy_row = [](double *to, const double *from) {
            copy_pairs(to, from, 6);
            to[6] = from[6];
        };
        size_t r = 0;
        for (; r + 2 <= rows; r += 2) {  // two per turn: the loop's count and branch halved
            copy_row(ws + row_to[r], values + row_from[r]);
            copy_row(ws + row_to[r + 1], values + row_from[r + 1]);
        }
        if (r < rows) copy_row(ws + row_to[r], values + row_from[r]);
        for (size_t r = 0; r < other_from_.size(); ++r) {
            const double *from = values + other_from_[r];
            double *to = ws + other_to_[r];
            for (int i = 0; i < other_length_[r]; ++i) to[i] = from[i];
        }
        // A fixed body's whole row (a joint's row of the ground) is the common run: copied
        // unrolled, since the general loop became a memmove call per run.
        const size_t *const start = coupling_start_.data();
        const int *const coupling_from = coupling_from_.data();
        double *const coupling = coupling_.data();
        for (size_t r = 0; r + 1 < coupling_start_.size(); ++r) {
            const size_t k = start[r], n = start[r + 1] - k;
            const double *from = values + coupling_from[k];
            if (n == MBS_BODY_COORDINATES) {
                copy_pairs(coupling + k, from, 6);
                coupling[k + 6] = from[6];
            } else {
                copy_pairs(coupling + k, from, n);
            }
        }
    }

    // The groups in vector lanes, factored by their program set by set; static_used_ says which
    // lanes kept the fixed pivot order.
    void factor_lane_sets(const double *values) {
        for (const LaneSet &s : lanes_.sets) {
            const unsigned refused =
                kernels_->factor(lane_ws_.data() + s.offset, s.lead->program,
                                 lane_inv_.data() + s.pivots, values, s.entries.data(),
                                 s.gather.data(), static_cast<int>(s.entries.size()), s.fill.data(),
                                 static_cast<int>(s.fill.size()));
            for (size_t l = 0; l < s.groups.size(); ++l)
                static_used_[s.groups[l]] = !((refused >> l) & 1u);
        }
    }

    // The other groups by their program, or by partial pivoting where the program's fixed pivot
    // order is unsafe (fell_back then true), and every group's leftover rows' border columns into
    // the border system. False if a block is singular.
    bool factor_groups(const double *values, bool &fell_back) {
        const int nb = p_.border;
        double *border = ws_.data() + p_.border_offset;
        for (const BlockGroup &g : p_.groups) {
            const int mg = static_cast<int>(g.rows.size()), ng = static_cast<int>(g.cols.size());
            double *a = ws_.data() + g.offset;
            const size_t gi = &g - p_.groups.data();
            if (lanes_.set_of[gi] < 0)
                static_used_[gi] =
                    g.has_program &&
                    lu_factor_static(a, g.program, inv_diag_.data() + g.pivot_offset);
            if (!static_used_[gi]) {
                // The fixed pivot order is unsafe here: partial pivoting on fresh values.
                std::fill(a, a + mg * (ng + nb), 0.0);
                for (size_t v = 0; v < g.value_index.size(); ++v)
                    ws_[g.value_dest[v]] = values[g.value_index[v]];
                dirty_[gi] = 1;
                ++fallbacks_;
                fell_back = true;
                if (!lu_factor(a, mg, ng, ng + nb, pivot_.data() + g.pivot_offset)) return false;
            }
            if (in_lane(gi)) {  // its leftover rows' border columns, from its lane
                const LaneSet &s = lanes_.sets[lanes_.set_of[gi]];
                const int L = lanes_.lanes;
                for (int r = ng; r < mg; ++r) {
                    const double *from =
                        lane_ws_.data() + s.offset + (r * s.width + ng) * L + lanes_.lane_of[gi];
                    double *to = border + (g.first_leftover + r - ng) * nb;
                    for (int c = 0; c < nb; ++c) to[c] = from[c * L];
                }
                continue;
            }
            for (int r = ng; r < mg; ++r) {
                const double *from = a + r * (ng + nb) + ng;
                double *to = border + (g.first_leftover + r - ng) * nb;
                if (nb == kOneHub) {  // one hub's 7 values, unrolled (std::copy called memmove)
                    copy_pairs(to, from, 6);
                    to[6] = from[6];
                } else {
                    std::copy(from, from + nb, to);
                }
            }
        }
        return true;
    }

    enum Path : char { kLane, kStatic, kPivoted };
    // One group's part of the solves: its path and where its vectors are, in its lane (stride
    // L) or its own (stride 1), so that one loop takes lane and scalar groups alike.
    struct GroupStep {
        Path path;
        int stride;
        double *t;        // its right-hand side: row r at t[r * stride]
        double *carried;  // its -W^T mu (transposed): border column c at carried[c * stride]
    };
    // steps_ from static_used_ (every group on its planned path at first).
    void choose_steps() {
        const int L = lanes_.lanes;
        for (size_t gi = 0; gi < p_.groups.size(); ++gi) {
            GroupStep &step = steps_[gi];
            if (in_lane(gi)) {
                const LaneSet &s = lanes_.sets[lanes_.set_of[gi]];
                step = {kLane, L, lane_t_.data() + s.vectors + lanes_.lane_of[gi],
                        lane_carried_.data() + s.carried + lanes_.lane_of[gi]};
            } else {
                step = {static_used_[gi] ? kStatic : kPivoted, 1,
                        group_t_.data() + group_t_offset_[gi], border_work_.data()};
            }
        }
    }
    // True if group gi was factored in its lane (false on a fallback: its scalar block holds it).
    bool in_lane(size_t gi) const { return lanes_.set_of[gi] >= 0 && static_used_[gi]; }
    const Mechanism &m_;
    const BlockPlan &p_;
    const LaneKernels *kernels_;
    LaneLayout lanes_;
    std::vector<double> lane_ws_, lane_inv_, lane_t_, lane_x_, lane_carried_;  // interleaved
    std::vector<int> group_t_offset_;  // per group: its right-hand side's place in group_t_
    std::vector<double> ws_, coupling_;
    std::vector<int> pivot_;
    std::vector<double> inv_diag_;  // reciprocal pivots of the groups factored by their program
    std::vector<int> border_pivot_;
    std::vector<double> rhs_, group_t_, border_, border_work_, group_x_;
    std::vector<int> coupling_fixed_row_;
    std::vector<char> static_used_;  // per group: factored with its fixed pivot order
    std::vector<char> dirty_;        // per group: partial pivoting wrote all over its block
    std::vector<GroupStep> steps_;   // per group: its path in the solves (choose_steps)
    bool steps_stale_ = true;        // steps_ may not match static_used_
    long fallbacks_ = 0;             // group factorisations that took partial pivoting
    // Jacobian values -> workspace: a body's whole rows (7 values from row_from_ to row_to_) and
    // the other runs (other_length_ values from other_from_ to other_to_).
    std::vector<int> row_from_, row_to_, other_from_, other_to_, other_length_, coupling_from_;
    // Runs of coupling values: [coupling_start_[r], coupling_start_[r + 1]) share their equation
    // and have neighbouring sources and fixed rows.
    std::vector<size_t> coupling_start_;
};

}  // namespace

std::unique_ptr<LinearSolver> make_linear_solver(const Mechanism &m, LinearSolverKind kind) {
    if (kind != LinearSolverKind::Dense && m.block_plan) {
        // The families once: they choose the kernels, then the sets are laid out for them.
        const std::vector<int> family = lane_families(*m.block_plan);
        const LaneKernels &kernels = lane_kernels_for(largest_family(family));
        return std::make_unique<BlockSolver>(m, &kernels,
                                             plan_lane_sets(*m.block_plan, family, kernels.lanes));
    }
    if (kind == LinearSolverKind::Block && !m.block_plan) return nullptr;
    return std::make_unique<DenseSolver>(m);
}

std::unique_ptr<LinearSolver> make_block_solver(const Mechanism &m, const LaneKernels *lanes) {
    if (!m.block_plan) return nullptr;
    return std::make_unique<BlockSolver>(m, lanes,
                                         plan_lane_sets(*m.block_plan, lanes ? lanes->lanes : 0));
}

}  // namespace mbs
