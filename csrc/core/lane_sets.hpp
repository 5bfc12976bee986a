// Which group blocks of a bordered-block plan share a vector register (lane_lu.hpp): groups
// whose elimination programs, fill and value positions are the same (a hexapod's legs), packed
// in group order into sets of at most `lanes`, with the interleaved workspace of each set.
#pragma once

#include <vector>

#include "core/linear_solver.hpp"

namespace mbs {

struct LaneSet {
    std::vector<int> groups;           // its groups, in group order; lane l is groups[l]
    const BlockGroup *lead = nullptr;  // groups[0]: its program and shape serve every lane
    int mg = 0, ng = 0, width = 0;
    int offset = 0;             // interleaved block: entry e of lane l at offset + e L + l
    int pivots = 0;             // reciprocal pivots: pivot k of lane l at pivots + k L + l
    int vectors = 0;            // right-hand sides: row r of lane l at vectors + r L + l
    int carried = 0;            // -W^T mu: border column c of lane l at carried + c L + l
    std::vector<long> entries;  // where (in doubles: entry e L) a Jacobian value lands
    std::vector<int> gather;    // per entry and lane: the value's index (pad lanes: lane 0's)
    std::vector<long> fill;     // where the program fills and no value lands
    // Per lane l (pad lanes: lane 0's group): at c L + l the coordinate of the group's column c,
    // at r L + l the equation of its row r (pivot order), at l its first leftover row.
    std::vector<int> col_of, row_of, first_leftover;
};

struct LaneLayout {
    int lanes = 0;
    std::vector<LaneSet> sets;
    std::vector<int> set_of, lane_of;                         // per group: its set and lane, or -1
    int workspace = 0, pivots = 0, vectors = 0, carried = 0;  // sizes of the interleaved arrays
};

// Per group, the first group whose program, fill and value places it shares (itself if no
// earlier one does), or -1 if it has no program: which groups one lane set may hold.
std::vector<int> lane_families(const BlockPlan &p);
// The most groups of one family (what one pass of the lane kernels could take).
int largest_family(const std::vector<int> &family);
// Sets of two or more groups of one family (`family` from lane_families); none when lanes < 2.
LaneLayout plan_lane_sets(const BlockPlan &p, const std::vector<int> &family, int lanes);
// The same, finding the families.
LaneLayout plan_lane_sets(const BlockPlan &p, int lanes);

}  // namespace mbs
