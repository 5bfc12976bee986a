// Planning the bordered-block LU (linear_solver.hpp `plan_blocks`): the border, the groups, their
// rows, their pivot orders and programs, the workspace and the fill, in named stages. Runs once
// per mechanism, when it is finalised.
#include <algorithm>
#include <random>
#include <set>
#include <utility>

#include "core/assembly.hpp"
#include "core/linear_solver.hpp"

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
void sample_jacobian(const Mechanism &m, std::vector<double> &reference,
                     std::vector<char> &nonzero) {
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
            for (int c = 0; c < MBS_BODY_COORDINATES; ++c)
                p.groups[g].cols.push_back(body_column(u, c));
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
            if (g >= 0) p.groups[g].rows.push_back(row);
            else p.border_rows.push_back(row);
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
            const int c = group_col[col] >= 0   ? group_col[col]
                          : col_local[col] >= 0 ? ng + col_local[col]
                                                : -1;
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

// The number of distinct group shapes (rows, columns): the fewest families there can be.
int count_shapes(const BlockPlan &p) {
    std::set<std::pair<size_t, size_t>> shapes;
    for (const BlockGroup &g : p.groups) shapes.emplace(g.rows.size(), g.cols.size());
    return static_cast<int>(shapes.size());
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
        alike = alike && !own[i].empty() && same_program(own_program[i], own_program[0]);
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
        if (!order.empty()) take_order(p.groups[members[i]], sample, order, common_nz, common);
        else take_order(p.groups[members[i]], sample, own[i], own_nz[i], own_program[i]);
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
    std::vector<int> family;
    const int families = find_families(p, samples, family);
    // Sorting can join only groups of one shape: with one family per shape it has nothing to do.
    if (families > count_shapes(p)) {
        std::vector<GroupSample> sorted = rows_by_where_values_land(p, samples);
        std::vector<int> family_sorted;
        if (find_families(p, sorted, family_sorted) < families) {
            samples.swap(sorted);
            family.swap(family_sorted);
        }
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
        p.workspace +=
            static_cast<int>(g.rows.size()) * (static_cast<int>(g.cols.size()) + p.border);
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
}  // namespace mbs
