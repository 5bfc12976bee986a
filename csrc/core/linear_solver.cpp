#include "core/linear_solver.hpp"

#include <algorithm>
#include <cstring>
#include <random>
#include <set>

#include "core/assembly.hpp"
#include "core/dense_lu.hpp"
#include "core/lane_lu.hpp"
#include "core/lane_sets.hpp"

namespace mbs {

namespace {

// Rows that are a fixed body's identity, and which coordinate each one fixes.
void fixed_body_rows(const Mechanism &m, std::vector<int> &rows, std::vector<int> &cols) {
    for (size_t k = 0; k < m.joints.size(); ++k)
        if (m.joints[k].type == JointType::FixedBody)
            for (int c = 0; c < 7; ++c) {
                rows.push_back(m.first_row[k] + c);
                cols.push_back(body_column(m.joints[k].body_i, c));
            }
}

// Jacobian values at the reference configuration, and which are structurally nonzero: nonzero
// at the reference or at random configurations (zeros at all of them are structural).
void sample_jacobian(const Mechanism &m, std::vector<double> &reference, std::vector<char> &nonzero) {
    std::vector<double> q(m.coordinates), values(m.values());
    std::vector<DriverValue> drive(m.drivers);
    place_at_reference(m, q.data());
    reference.assign(m.values(), 0.0);
    assemble_jacobian(m, q.data(), drive.data(), reference.data());
    nonzero.assign(m.values(), 0);
    for (int t = 0; t < m.values(); ++t) nonzero[t] = reference[t] != 0.0;
    std::mt19937 random(20201);  // fixed seed: the plan is reproducible
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    for (int sample = 0; sample < 3; ++sample) {
        for (double &v : q) v += 0.3 * uniform(random);
        for (DriverValue &d : drive) d.value = uniform(random);
        assemble_jacobian(m, q.data(), drive.data(), values.data());
        for (int t = 0; t < m.values(); ++t) nonzero[t] |= values[t] != 0.0;
    }
}

}  // namespace

namespace {

// What the planning stages share: the plan being built and the maps from bodies and rows to it.
struct Planning {
    const Mechanism &m;
    BlockPlan &p;
    std::vector<std::set<int>> neighbours;  // per body: the free bodies joined to it
    std::vector<int> border_index;          // per body: its index among the hubs, else -1
    std::vector<int> group_of;              // per body: its group, else -1
    std::vector<int> row_group;             // per row: its group, -1 border row, -2 fixed body
    int leftover = 0;                       // rows of the groups beyond their unknowns
};

// Stage 1, the border: free bodies joined to three or more other free bodies (hubs). False if
// there is none (no bordered structure).
bool find_border(Planning &pl) {
    const Mechanism &m = pl.m;
    const int nbodies = static_cast<int>(m.bodies.size());
    pl.neighbours.assign(nbodies, {});
    for (const JointDef &j : m.joints)
        if (j.body_j >= 0 && !m.bodies[j.body_i].fixed && !m.bodies[j.body_j].fixed) {
            pl.neighbours[j.body_i].insert(j.body_j);
            pl.neighbours[j.body_j].insert(j.body_i);
        }
    pl.border_index.assign(nbodies, -1);
    for (int b = 0; b < nbodies; ++b)
        if (!m.bodies[b].fixed && pl.neighbours[b].size() >= 3) {
            pl.border_index[b] = static_cast<int>(pl.p.border_cols.size()) / MBS_BODY_COORDINATES;
            for (int c = 0; c < MBS_BODY_COORDINATES; ++c)
                pl.p.border_cols.push_back(body_column(b, c));
        }
    pl.p.border = static_cast<int>(pl.p.border_cols.size());
    return pl.p.border > 0;
}

// Stage 2, the groups: connected components of the free bodies off the border.
void find_groups(Planning &pl) {
    const Mechanism &m = pl.m;
    BlockPlan &p = pl.p;
    const int nbodies = static_cast<int>(m.bodies.size());
    pl.group_of.assign(nbodies, -1);
    for (int b = 0; b < nbodies; ++b) {
        if (m.bodies[b].fixed || pl.border_index[b] >= 0 || pl.group_of[b] >= 0) continue;
        const int g = static_cast<int>(p.groups.size());
        p.groups.emplace_back();
        std::vector<int> stack{b};
        pl.group_of[b] = g;
        while (!stack.empty()) {
            const int u = stack.back();
            stack.pop_back();
            for (int c = 0; c < MBS_BODY_COORDINATES; ++c) p.groups[g].cols.push_back(body_column(u, c));
            for (int v : pl.neighbours[u])
                if (pl.border_index[v] < 0 && pl.group_of[v] < 0) {
                    pl.group_of[v] = g;
                    stack.push_back(v);
                }
        }
    }
}

// Stage 3, the rows: each equation goes to the group whose bodies it touches, else to the border.
// False unless every group has at least as many rows as unknowns and its extra rows together
// with the border rows make a square border system.
bool assign_rows(Planning &pl) {
    const Mechanism &m = pl.m;
    BlockPlan &p = pl.p;
    pl.row_group.assign(m.equations, -2);
    for (size_t k = 0; k < m.joints.size(); ++k) {
        const JointDef &j = m.joints[k];
        if (j.type == JointType::FixedBody) continue;
        int g = -1;
        for (int b : {j.body_i, j.body_j})
            if (b >= 0 && pl.group_of[b] >= 0) g = pl.group_of[b];
        const int n = joint_type(j.type).equations;
        for (int r = 0; r < n; ++r) {
            const int row = m.first_row[k] + r;
            pl.row_group[row] = g;
            if (g >= 0)
                p.groups[g].rows.push_back(row);
            else
                p.border_rows.push_back(row);
        }
    }
    pl.leftover = 0;
    for (BlockGroup &g : p.groups) {
        if (g.rows.size() < g.cols.size()) return false;
        g.first_leftover = pl.leftover;
        pl.leftover += static_cast<int>(g.rows.size() - g.cols.size());
    }
    return pl.leftover + static_cast<int>(p.border_rows.size()) == p.border;
}

// A group's block at the reference configuration, for stage 4.
struct GroupSample {
    std::vector<double> a;    // reference values, row-major, rows in the order of `rows`
    std::vector<int> rows;    // the group's rows
    std::vector<char> nz;     // structural nonzeros
    std::vector<char> lands;  // where any Jacobian value lands
};

std::vector<GroupSample> sample_groups(const Planning &pl, const std::vector<double> &reference) {
    const Mechanism &m = pl.m;
    const BlockPlan &p = pl.p;
    std::vector<int> row_local(m.equations, -1), col_local(m.coordinates, -1);
    for (int c = 0; c < p.border; ++c) col_local[p.border_cols[c]] = c;  // + n below
    std::vector<GroupSample> samples(p.groups.size());
    for (size_t gi = 0; gi < p.groups.size(); ++gi) {
        const BlockGroup &g = p.groups[gi];
        const int mg = static_cast<int>(g.rows.size()), ng = static_cast<int>(g.cols.size());
        const int width = ng + p.border;
        GroupSample &sample = samples[gi];
        sample.a.assign(mg * width, 0.0);
        sample.nz.assign(mg * width, 0);
        sample.lands.assign(mg * width, 0);
        sample.rows = g.rows;
        for (int r = 0; r < mg; ++r) row_local[g.rows[r]] = r;
        std::vector<int> group_col(m.coordinates, -1);
        for (int c = 0; c < ng; ++c) group_col[g.cols[c]] = c;
        for (int t = 0; t < m.values(); ++t) {
            const int row = m.pattern_row[t], col = m.pattern_col[t];
            if (pl.row_group[row] != static_cast<int>(gi)) continue;
            const int c = group_col[col] >= 0 ? group_col[col]
                          : col_local[col] >= 0 ? ng + col_local[col] : -1;
            if (c < 0) continue;  // a fixed body's column
            sample.a[row_local[row] * width + c] = reference[t];
            sample.nz[row_local[row] * width + c] = p.structural[t];
            sample.lands[row_local[row] * width + c] = 1;
        }
    }
    return samples;
}

// The same samples with each group's rows sorted by where their values land (stable: joint
// order among equals), so that groups of one shape list their rows alike whatever order their
// joints came in.
std::vector<GroupSample> rows_by_where_values_land(const BlockPlan &p,
                                                   std::vector<GroupSample> samples) {
    for (size_t gi = 0; gi < samples.size(); ++gi) {
        const int mg = static_cast<int>(p.groups[gi].rows.size());
        const int width = static_cast<int>(p.groups[gi].cols.size()) + p.border;
        GroupSample &sample = samples[gi];
        std::vector<int> perm(mg);
        for (int r = 0; r < mg; ++r) perm[r] = r;
        const std::vector<char> lands = sample.lands;
        std::stable_sort(perm.begin(), perm.end(), [&](int x, int y) {
            return std::lexicographical_compare(lands.begin() + y * width,
                                                lands.begin() + (y + 1) * width,
                                                lands.begin() + x * width,
                                                lands.begin() + (x + 1) * width);
        });
        auto permute = [&](auto &v) {
            const auto copy = v;
            for (int r = 0; r < mg; ++r)
                std::copy(copy.begin() + perm[r] * width, copy.begin() + (perm[r] + 1) * width,
                          v.begin() + r * width);
        };
        permute(sample.a), permute(sample.nz), permute(sample.lands);
        for (int r = 0; r < mg; ++r) sample.rows[r] = p.groups[gi].rows[perm[r]];
    }
    return samples;
}

// Per group, the first group of its family (same shape, values landing on the same places);
// returns the number of families.
int find_families(const BlockPlan &p, const std::vector<GroupSample> &samples,
                  std::vector<int> &family) {
    const int ngroups = static_cast<int>(p.groups.size());
    int count = 0;
    family.assign(ngroups, 0);
    for (int gi = 0; gi < ngroups; ++gi) {
        family[gi] = gi;
        for (int f = 0; f < gi && family[gi] == gi; ++f)
            if (family[f] == f && p.groups[f].rows.size() == p.groups[gi].rows.size() &&
                p.groups[f].cols.size() == p.groups[gi].cols.size() &&
                samples[f].lands == samples[gi].lands)
                family[gi] = f;
        count += family[gi] == gi;
    }
    return count;
}

// The group's program and its rows in pivot order.
void take_order(BlockGroup &g, const GroupSample &sample, const std::vector<int> &order,
                const std::vector<char> &structure, const EliminationProgram &program) {
    g.program = program;
    g.has_program = !order.empty();
    g.structure = structure;
    if (g.has_program) {
        std::vector<int> rows(order.size());
        for (size_t r = 0; r < order.size(); ++r) rows[r] = sample.rows[order[r]];
        g.rows = rows;
    }
}

// One family's orders on the union of its structures (`nz`): each member's own if their programs
// agree (orders that swap rows of one structure may give one program), else one order whose
// pivots pass the threshold in every member's reference sample, and if there is none, each its
// own after all. (Asking the common order to suit the random samples too found none, for the
// platform or for test_block_solver's hexapod.)
void order_family(BlockPlan &p, const std::vector<GroupSample> &samples,
                  const std::vector<int> &members, const std::vector<char> &nz) {
    const BlockGroup &first = p.groups[members[0]];
    const int mg = static_cast<int>(first.rows.size()), ng = static_cast<int>(first.cols.size()),
              width = ng + p.border;
    std::vector<std::vector<int>> own(members.size());
    std::vector<std::vector<char>> own_nz(members.size(), nz);
    std::vector<EliminationProgram> own_program(members.size());
    bool alike = true;
    for (size_t i = 0; i < members.size(); ++i) {
        std::vector<double> a = samples[members[i]].a;
        own[i] = choose_pivot_order(a, own_nz[i], mg, ng, width, own_program[i]);
        const EliminationProgram &a0 = own_program[0], &ai = own_program[i];
        alike = alike && !own[i].empty() && ai.below_start == a0.below_start &&
                ai.below == a0.below && ai.span_begin == a0.span_begin &&
                ai.span_end == a0.span_end;
    }
    std::vector<char> common_nz = nz;
    EliminationProgram common;
    std::vector<int> order;
    if (!alike) {
        std::vector<std::vector<double>> a;
        for (int gi : members) a.push_back(samples[gi].a);
        order = choose_common_pivot_order(a, common_nz, mg, ng, width, common);
    }
    for (size_t i = 0; i < members.size(); ++i) {
        const GroupSample &sample = samples[members[i]];
        if (!order.empty())
            take_order(p.groups[members[i]], sample, order, common_nz, common);
        else
            take_order(p.groups[members[i]], sample, own[i], own_nz[i], own_program[i]);
    }
}

// Stage 4, the pivot order and elimination program of each group, from sample values. Groups
// whose Jacobian values land on the same places of their blocks (the legs of a hexapod) form a
// family with the union of their structures and, where it can, one program (order_family), so
// that the lane kernels (lane_lu.hpp) factor their blocks side by side. Rows are sorted by where
// their values land only where that joins more groups into families than the joint order does
// (it changes the order, so the pivots, of mechanisms whose joint order lists them alike).
void choose_group_orders(Planning &pl) {
    BlockPlan &p = pl.p;
    std::vector<double> reference;
    sample_jacobian(pl.m, reference, p.structural);
    std::vector<GroupSample> samples = sample_groups(pl, reference);
    std::vector<GroupSample> sorted = rows_by_where_values_land(p, samples);
    std::vector<int> family, family_sorted;
    if (find_families(p, sorted, family_sorted) < find_families(p, samples, family)) {
        samples.swap(sorted);
        family.swap(family_sorted);
    }
    const int ngroups = static_cast<int>(p.groups.size());
    for (int f = 0; f < ngroups; ++f) {
        if (family[f] != f) continue;
        std::vector<int> members;
        std::vector<char> nz = samples[f].nz;
        for (int gi = f; gi < ngroups; ++gi)
            if (family[gi] == f) {
                members.push_back(gi);
                for (size_t i = 0; i < nz.size(); ++i) nz[i] |= samples[gi].nz[i];
            }
        order_family(p, samples, members, nz);
    }
}

// Stage 5, the workspace: each group's block, then the border system, and where each Jacobian
// value lands (value_dest; fixed columns become coupling entries). False if a value falls
// outside the blocks.
bool lay_out_workspace(Planning &pl) {
    const Mechanism &m = pl.m;
    BlockPlan &p = pl.p;
    for (BlockGroup &g : p.groups) {
        g.offset = p.workspace;
        g.pivot_offset = p.pivots;
        p.workspace += static_cast<int>(g.rows.size()) * (static_cast<int>(g.cols.size()) + p.border);
        p.pivots += static_cast<int>(g.cols.size());
    }
    p.border_offset = p.workspace;
    p.workspace += p.border * p.border;
    std::vector<int> local_row(m.equations, -1), local_col(m.coordinates, -1),
        border_col(m.coordinates, -1), fixed_col(m.coordinates, 0);
    for (const BlockGroup &g : p.groups) {
        for (size_t r = 0; r < g.rows.size(); ++r) local_row[g.rows[r]] = static_cast<int>(r);
        for (size_t c = 0; c < g.cols.size(); ++c) local_col[g.cols[c]] = static_cast<int>(c);
    }
    for (size_t r = 0; r < p.border_rows.size(); ++r)
        local_row[p.border_rows[r]] = pl.leftover + static_cast<int>(r);
    for (int c = 0; c < p.border; ++c) border_col[p.border_cols[c]] = c;
    for (int c : p.fixed_cols) fixed_col[c] = 1;
    for (int t = 0; t < m.values(); ++t) {
        const int row = m.pattern_row[t], col = m.pattern_col[t];
        const int g = pl.row_group[row];
        int dest = -1;
        if (g == -2) {
            dest = -1;  // identity rows of fixed bodies are known
        } else if (fixed_col[col]) {
            dest = -2 - static_cast<int>(p.coupling_row.size());
            p.coupling_row.push_back(row);
            p.coupling_col.push_back(col);
        } else if (g >= 0) {
            const BlockGroup &grp = p.groups[g];
            const int n = static_cast<int>(grp.cols.size());
            const int c = (pl.group_of[col / 7] == g) ? local_col[col] : n + border_col[col];
            if (c < 0) return false;
            dest = grp.offset + local_row[row] * (n + p.border) + c;
            p.groups[g].value_index.push_back(t);
            p.groups[g].value_dest.push_back(dest);
        } else {
            if (border_col[col] < 0) return false;
            dest = p.border_offset + local_row[row] * p.border + border_col[col];
        }
        p.value_dest.push_back(dest);
    }
    return true;
}

// Stage 6, the fill: positions a group's program writes but no value lands on, zeroed before
// each refactorisation (nothing else is ever written there).
void find_fill(BlockPlan &p) {
    for (BlockGroup &g : p.groups) {
        if (!g.has_program) continue;
        const int width = static_cast<int>(g.cols.size()) + p.border;
        std::vector<char> scattered(g.rows.size() * width, 0);
        for (size_t v = 0; v < g.value_dest.size(); ++v) scattered[g.value_dest[v] - g.offset] = 1;
        for (size_t i = 0; i < scattered.size(); ++i)
            if (g.structure[i] && !scattered[i]) g.fill.push_back(g.offset + static_cast<int>(i));
    }
}

}  // namespace

std::shared_ptr<const BlockPlan> plan_blocks(const Mechanism &m) {
    auto plan = std::make_shared<BlockPlan>();
    Planning pl{m, *plan, {}, {}, {}, {}, 0};
    fixed_body_rows(m, plan->fixed_rows, plan->fixed_cols);
    if (!find_border(pl)) return nullptr;
    find_groups(pl);
    if (!assign_rows(pl)) return nullptr;
    choose_group_orders(pl);
    if (!lay_out_workspace(pl)) return nullptr;
    find_fill(*plan);
    return plan;
}

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
inline void scatter_rows(double *__restrict x, const double *__restrict t, const int *rows,
                         int n) {
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
    // kernels: the lane kernels for groups of the same shape, or null for one group at a time.
    BlockSolver(const Mechanism &m, const LaneKernels *kernels)
        : m_(m), p_(*m.block_plan), kernels_(kernels),
          lanes_(plan_lane_sets(p_, kernels ? kernels->lanes : 0)),
          lane_ws_(lanes_.workspace), lane_inv_(lanes_.pivots), lane_t_(lanes_.vectors),
          lane_x_(lanes_.vectors), lane_carried_(lanes_.carried),
          group_t_offset_(p_.groups.size()),
          ws_(p_.workspace), coupling_(p_.coupling_row.size()),
          pivot_(p_.pivots), inv_diag_(p_.pivots), border_pivot_(p_.border), rhs_(m.equations), group_t_(m.equations),
          border_(p_.border), border_work_(p_.border), group_x_(m.coordinates),
          coupling_fixed_row_(p_.coupling_row.size()), static_used_(p_.groups.size(), 0),
          dirty_(p_.groups.size(), 0) {
        // Fixed coordinate -> its identity row, for the transposed solve.
        std::vector<int> row_of(m.coordinates, -1);
        for (size_t i = 0; i < p_.fixed_cols.size(); ++i) row_of[p_.fixed_cols[i]] = p_.fixed_rows[i];
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
                          in_lanes.begin() + g.offset + g.rows.size() * (g.cols.size() + p_.border), 1);
        }
        int t_offset = 0;
        for (size_t gi = 0; gi < p_.groups.size(); ++gi) {
            group_t_offset_[gi] = t_offset;
            t_offset += static_cast<int>(p_.groups[gi].rows.size());
        }
        std::vector<int> run_from, run_to, run_length;
        for (int t = 0; t < m.values(); ++t) {
            const int d = p_.value_dest[t] >= 0 && in_lanes[p_.value_dest[t]] ? -1 : p_.value_dest[t];
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

    bool factor(const double *values) override {
        // Blocks factored by their program keep zeros wherever the program does not write; only
        // the fill needs clearing. Others (and the border system) are cleared whole.
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
        const int nb = p_.border;
        double *border = ws_.data() + p_.border_offset;
        for (const LaneSet &s : lanes_.sets) {
            const unsigned refused = kernels_->factor(
                lane_ws_.data() + s.offset, s.lead->program, lane_inv_.data() + s.pivots, values,
                s.entries.data(), s.gather.data(), static_cast<int>(s.entries.size()),
                s.fill.data(), static_cast<int>(s.fill.size()));
            for (size_t l = 0; l < s.groups.size(); ++l)
                static_used_[s.groups[l]] = !((refused >> l) & 1u);
        }
        for (const BlockGroup &g : p_.groups) {
            const int mg = static_cast<int>(g.rows.size()), ng = static_cast<int>(g.cols.size());
            double *a = ws_.data() + g.offset;
            const size_t gi = &g - p_.groups.data();
            if (lanes_.set_of[gi] < 0)
                static_used_[gi] = g.has_program &&
                                   lu_factor_static(a, g.program, inv_diag_.data() + g.pivot_offset);
            if (!static_used_[gi]) {
                // The fixed pivot order is unsafe here: partial pivoting on fresh values.
                std::fill(a, a + mg * (ng + nb), 0.0);
                for (size_t v = 0; v < g.value_index.size(); ++v)
                    ws_[g.value_dest[v]] = values[g.value_index[v]];
                dirty_[gi] = 1;
                ++fallbacks_;
                if (!lu_factor(a, mg, ng, ng + nb, pivot_.data() + g.pivot_offset)) return false;
            }
            if (in_lane(gi)) {  // its leftover rows' border columns, from its lane
                const LaneSet &s = lanes_.sets[lanes_.set_of[gi]];
                const int L = lanes_.lanes;
                for (int r = ng; r < mg; ++r) {
                    const double *from = lane_ws_.data() + s.offset + (r * s.width + ng) * L +
                                         lanes_.lane_of[gi];
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
            for (int l = 0; l < L; ++l) {
                const std::vector<int> &rows = lane_group(s, l).rows;
                for (int r = 0; r < s.mg; ++r) t[r * L + l] = rhs_[rows[r]];
            }
            kernels_->forward(lane_ws_.data() + s.offset, s.lead->program, t);
        }
        for (const BlockGroup &g : p_.groups) {
            const int mg = static_cast<int>(g.rows.size()), ng = static_cast<int>(g.cols.size());
            const size_t gi = &g - p_.groups.data();
            if (in_lane(gi)) {
                const double *t = lane_t_.data() + lanes_.sets[lanes_.set_of[gi]].vectors +
                                  lanes_.lane_of[gi];
                for (int r = ng; r < mg; ++r) border_[g.first_leftover + r - ng] = t[r * L];
                continue;
            }
            double *t = group_t_.data() + group_t_offset_[gi];
            for (int r = 0; r < mg; ++r) t[r] = rhs_[g.rows[r]];
            if (static_used_[gi])
                lu_forward_static(ws_.data() + g.offset, g.program, t);
            else
                lu_forward(ws_.data() + g.offset, mg, ng, ng + nb, pivot_.data() + g.pivot_offset, t);
            for (int r = ng; r < mg; ++r) border_[g.first_leftover + r - ng] = t[r];
        }
        const int leftover = nb - static_cast<int>(p_.border_rows.size());
        for (size_t r = 0; r < p_.border_rows.size(); ++r) border_[leftover + r] = rhs_[p_.border_rows[r]];
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
            const size_t gi = &g - p_.groups.data();
            if (in_lane(gi)) continue;
            const double *t = group_t_.data() + group_t_offset_[gi];
            if (static_used_[gi])
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
        const int nb = p_.border, L = lanes_.lanes;
        for (int c = 0; c < nb; ++c) border_[c] = rhs_[p_.border_cols[c]];
        for (const LaneSet &s : lanes_.sets) {
            double *mu = lane_t_.data() + s.vectors;
            for (int l = 0; l < L; ++l) {
                const std::vector<int> &cols = lane_group(s, l).cols;
                for (int c = 0; c < s.ng; ++c) mu[c * L + l] = rhs_[cols[c]];
            }
            kernels_->forward_transposed(lane_ws_.data() + s.offset, s.lead->program,
                                         lane_inv_.data() + s.pivots, mu,
                                         lane_carried_.data() + s.carried);
        }
        // Each group's -W^T mu, from zero, added to the border in group order: the lanes make
        // theirs side by side, one group at a time the same sums.
        for (const BlockGroup &g : p_.groups) {
            const int ng = static_cast<int>(g.cols.size());
            const size_t gi = &g - p_.groups.data();
            if (in_lane(gi)) {
                const double *carried = lane_carried_.data() +
                                        lanes_.sets[lanes_.set_of[gi]].carried + lanes_.lane_of[gi];
                for (int c = 0; c < nb; ++c) border_[c] += carried[c * L];
                continue;
            }
            double *t = group_t_.data() + group_t_offset_[gi];
            const double *a = ws_.data() + g.offset;
            gather_bodies(group_x_.data(), rhs_.data(), g.cols.data(), ng);
            if (static_used_[gi]) {
                double *carried = border_work_.data();
                std::fill(carried, carried + nb, 0.0);
                lu_forward_transposed_static(a, g.program, inv_diag_.data() + g.pivot_offset,
                                             group_x_.data(), t, carried);
                for (int c = 0; c < nb; ++c) border_[c] += carried[c];
            } else {
                lu_forward_transposed(a, ng, ng + nb, group_x_.data(), t);
                for (int k = 0; k < ng; ++k) {
                    const double mu = t[k];
                    const double *w = a + k * (ng + nb) + ng;
                    for (int b = 0; b < nb; ++b) border_[b] -= w[b] * mu;
                }
            }
        }
        const double *s = ws_.data() + p_.border_offset;
        if (nb == kOneHub) {
            lu_solve_transposed_square<kOneHub>(s, border_pivot_.data(), border_.data(),
                                                border_work_.data());
        } else {
            lu_forward_transposed(s, nb, nb, border_.data(), border_work_.data());
            lu_backward_transposed(s, nb, nb, nb, border_pivot_.data(), border_work_.data());
        }
        for (const LaneSet &set : lanes_.sets) {
            double *t = lane_t_.data() + set.vectors;
            for (int l = 0; l < L; ++l) {
                const int first = lane_group(set, l).first_leftover - set.ng;
                for (int r = set.ng; r < set.mg; ++r) t[r * L + l] = border_work_[first + r];
            }
            kernels_->backward_transposed(lane_ws_.data() + set.offset, set.lead->program, t);
            for (size_t l = 0; l < set.groups.size(); ++l) {
                if (!static_used_[set.groups[l]]) continue;
                const std::vector<int> &rows = p_.groups[set.groups[l]].rows;
                for (int r = 0; r < set.mg; ++r) x[rows[r]] = t[r * L + l];
            }
        }
        for (const BlockGroup &g : p_.groups) {
            const int mg = static_cast<int>(g.rows.size()), ng = static_cast<int>(g.cols.size());
            const size_t gi = &g - p_.groups.data();
            if (in_lane(gi)) continue;
            double *t = group_t_.data() + group_t_offset_[gi];
            for (int r = ng; r < mg; ++r) t[r] = border_work_[g.first_leftover + r - ng];
            if (static_used_[gi])
                lu_backward_transposed_static(ws_.data() + g.offset, g.program, t);
            else
                lu_backward_transposed(ws_.data() + g.offset, mg, ng, ng + nb,
                                       pivot_.data() + g.pivot_offset, t);
            scatter_rows(x, t, g.rows.data(), mg);
        }
        const int leftover = nb - static_cast<int>(p_.border_rows.size());
        for (size_t r = 0; r < p_.border_rows.size(); ++r) x[p_.border_rows[r]] = border_work_[leftover + r];
        for (size_t i = 0; i < p_.fixed_cols.size(); ++i) x[p_.fixed_rows[i]] = rhs_[p_.fixed_cols[i]];
        // Run by run in k order: each fixed row takes the same differences in the same order. A
        // fixed body's whole row, the common run, unrolled.
        const size_t *const start = coupling_start_.data();
        const int *const fixed_row = coupling_fixed_row_.data(), *const row = p_.coupling_row.data();
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

    const char *name() const override { return "bordered block LU"; }
    long fallbacks() const override { return fallbacks_; }

private:
    // True if group gi was factored in its lane (false on a fallback: its scalar block holds it).
    bool in_lane(size_t gi) const { return lanes_.set_of[gi] >= 0 && static_used_[gi]; }
    // Lane l's group; a pad lane (beyond the set's groups) repeats lane 0's, so its values stay
    // those of a regular block.
    const BlockGroup &lane_group(const LaneSet &s, int l) const {
        return p_.groups[s.groups[l < static_cast<int>(s.groups.size()) ? l : 0]];
    }
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
    long fallbacks_ = 0;             // group factorisations that took partial pivoting
    // Jacobian values -> workspace: a body's whole rows (7 values from row_from_ to row_to_) and
    // the other runs (other_length_ values from other_from_ to other_to_).
    std::vector<int> row_from_, row_to_, other_from_, other_to_, other_length_, coupling_from_;
    // Runs of coupling values: [coupling_start_[r], coupling_start_[r + 1]) share their equation
    // and have neighbouring sources and fixed rows.
    std::vector<size_t> coupling_start_;
};

}  // namespace

namespace {
// The most groups that share one program (what one pass of the lane kernels could take).
int largest_family(const BlockPlan &p) {
    int largest = 1;
    for (const LaneSet &s : plan_lane_sets(p, static_cast<int>(p.groups.size())).sets)
        largest = std::max(largest, static_cast<int>(s.groups.size()));
    return largest;
}
}  // namespace

std::unique_ptr<LinearSolver> make_linear_solver(const Mechanism &m, LinearSolverKind kind) {
    if (kind != LinearSolverKind::Dense && m.block_plan)
        return std::make_unique<BlockSolver>(m, &lane_kernels_for(largest_family(*m.block_plan)));
    if (kind == LinearSolverKind::Block && !m.block_plan) return nullptr;
    return std::make_unique<DenseSolver>(m);
}

std::unique_ptr<LinearSolver> make_block_solver(const Mechanism &m, const LaneKernels *lanes) {
    if (!m.block_plan) return nullptr;
    return std::make_unique<BlockSolver>(m, lanes);
}

}  // namespace mbs
