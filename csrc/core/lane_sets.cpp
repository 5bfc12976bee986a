#include "core/lane_sets.hpp"

#include <algorithm>
#include <utility>

namespace mbs {

namespace {

// A group's values as (block entry, value index), by entry.
std::vector<std::pair<int, int>> entry_values(const BlockGroup &g) {
    std::vector<std::pair<int, int>> ev;
    for (size_t v = 0; v < g.value_dest.size(); ++v)
        ev.emplace_back(g.value_dest[v] - g.offset, g.value_index[v]);
    std::sort(ev.begin(), ev.end());
    return ev;
}

// True if the lane kernels may run b's block in a's program: the same shape, the same program
// (same_program), the same fill and values on the same entries.
bool same_shape(const BlockGroup &a, const BlockGroup &b,
                const std::vector<std::pair<int, int>> &ea,
                const std::vector<std::pair<int, int>> &eb) {
    if (!a.has_program || !b.has_program || a.rows.size() != b.rows.size() ||
        a.cols.size() != b.cols.size() || !same_program(a.program, b.program))
        return false;
    if (ea.size() != eb.size() || a.fill.size() != b.fill.size()) return false;
    for (size_t i = 0; i < ea.size(); ++i)
        if (ea[i].first != eb[i].first) return false;
    for (size_t i = 0; i < a.fill.size(); ++i)
        if (a.fill[i] - a.offset != b.fill[i] - b.offset) return false;
    return true;
}

}  // namespace

std::vector<int> lane_families(const BlockPlan &p) {
    const int ngroups = static_cast<int>(p.groups.size());
    std::vector<std::vector<std::pair<int, int>>> values(ngroups);
    for (int g = 0; g < ngroups; ++g) values[g] = entry_values(p.groups[g]);
    std::vector<int> family(ngroups, -1);
    for (int g = 0; g < ngroups; ++g) {
        if (!p.groups[g].has_program) continue;
        family[g] = g;
        for (int f = 0; f < g && family[g] == g; ++f)
            if (family[f] == f && same_shape(p.groups[f], p.groups[g], values[f], values[g]))
                family[g] = f;
    }
    return family;
}

int largest_family(const std::vector<int> &family) {
    std::vector<int> size(family.size(), 0);
    int largest = 1;
    for (int f : family)
        if (f >= 0) largest = std::max(largest, ++size[f]);
    return largest;
}

LaneLayout plan_lane_sets(const BlockPlan &p, int lanes) {
    return plan_lane_sets(p, lane_families(p), lanes);
}

LaneLayout plan_lane_sets(const BlockPlan &p, const std::vector<int> &family, int lanes) {
    LaneLayout out;
    out.lanes = lanes;
    const int ngroups = static_cast<int>(p.groups.size());
    out.set_of.assign(ngroups, -1);
    out.lane_of.assign(ngroups, -1);
    if (lanes < 2) return out;
    std::vector<std::vector<std::pair<int, int>>> values(ngroups);
    for (int g = 0; g < ngroups; ++g) values[g] = entry_values(p.groups[g]);
    for (int g = 0; g < ngroups; ++g) {
        if (out.set_of[g] >= 0 || family[g] < 0) continue;
        std::vector<int> members{g};
        for (int h = g + 1; h < ngroups && static_cast<int>(members.size()) < lanes; ++h)
            if (out.set_of[h] < 0 && family[h] == family[g]) members.push_back(h);
        if (members.size() < 2) continue;
        LaneSet s;
        s.groups = members;
        s.lead = &p.groups[g];
        s.mg = static_cast<int>(s.lead->rows.size());
        s.ng = static_cast<int>(s.lead->cols.size());
        s.width = s.ng + p.border;
        s.offset = out.workspace;
        s.pivots = out.pivots;
        s.vectors = out.vectors;
        s.carried = out.carried;
        out.carried += p.border * lanes;
        out.workspace += s.mg * s.width * lanes;
        out.pivots += s.ng * lanes;
        out.vectors += s.mg * lanes;
        for (const auto &ev : values[g]) s.entries.push_back(static_cast<long>(ev.first) * lanes);
        s.gather.resize(s.entries.size() * lanes);
        for (int l = 0; l < lanes; ++l) {
            const int from = l < static_cast<int>(members.size()) ? members[l] : g;
            for (size_t e = 0; e < s.entries.size(); ++e)
                s.gather[e * lanes + l] = values[from][e].second;
        }
        for (int f : s.lead->fill) s.fill.push_back(static_cast<long>(f - s.lead->offset) * lanes);
        s.col_of.resize(s.ng * lanes);
        s.row_of.resize(s.mg * lanes);
        s.first_leftover.resize(lanes);
        for (int l = 0; l < lanes; ++l) {
            const BlockGroup &lg = p.groups[l < static_cast<int>(members.size()) ? members[l] : g];
            for (int c = 0; c < s.ng; ++c) s.col_of[c * lanes + l] = lg.cols[c];
            for (int r = 0; r < s.mg; ++r) s.row_of[r * lanes + l] = lg.rows[r];
            s.first_leftover[l] = lg.first_leftover;
        }
        for (size_t l = 0; l < members.size(); ++l) {
            out.set_of[members[l]] = static_cast<int>(out.sets.size());
            out.lane_of[members[l]] = static_cast<int>(l);
        }
        out.sets.push_back(std::move(s));
    }
    return out;
}

}  // namespace mbs
