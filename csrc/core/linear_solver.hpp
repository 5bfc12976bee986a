// Linear solvers for the square constraint Jacobian Phi_q: J x = b (Newton steps, velocities,
// accelerations) and J^T x = b (multipliers), both on one factorisation.
//
// The block solver exploits a structure it detects (it knows nothing of any mechanism): fixed
// bodies are eliminated (their rows are an identity), "hub" bodies joined to three or more others
// form the border, and the rest fall apart into groups of bodies whose equations touch only their
// own coordinates and the border's. Each group's block is LU-factorised with its border columns
// carried along; the rows left over (equations minus unknowns of the group) form, with the
// border-only equations, a small dense border system. When the structure is not there, the
// dense LU is used.
#pragma once

#include <memory>
#include <vector>

#include "core/mechanism.hpp"
#include "core/sparse_lu.hpp"

namespace mbs {

struct BlockGroup {
    std::vector<int> rows, cols;  // global rows and coordinates (cols: whole bodies, 7 in a row)
    int offset = 0;               // of its m x (n + border) row-major block in the workspace
    int first_leftover = 0;       // its first row in the border system
    int pivot_offset = 0;
    bool has_program = false;  // rows are in a chosen pivot order with this program
    EliminationProgram program;
    std::vector<int> value_index, value_dest;  // its Jacobian values (for a re-scatter)
    std::vector<char> structure;  // m x width, in pivot order: structural nonzeros and fill
    std::vector<int> fill;        // workspace indices the program fills but no value lands on
};

struct BlockPlan {
    int border = 0;                // border unknowns
    std::vector<int> border_cols;  // their global coordinates
    std::vector<BlockGroup> groups;
    std::vector<int> border_rows;             // global rows of border-only equations
    std::vector<int> fixed_cols, fixed_rows;  // x[fixed_cols[i]] = b[fixed_rows[i]]
    std::vector<int> value_dest;              // per Jacobian value: workspace index, -1 ignored,
                                              // -2 - k: coupling entry k
    std::vector<int> coupling_row, coupling_col;  // values of fixed columns in other rows
    std::vector<char> structural;                 // per Jacobian value: not identically zero
    int workspace = 0, border_offset = 0, pivots = 0;
};

// Null when the mechanism has no bordered block structure.
std::shared_ptr<const BlockPlan> plan_blocks(const Mechanism &m);

class LinearSolver {
public:
    virtual ~LinearSolver() = default;
    // False if the matrix is (numerically) singular.
    virtual bool factor(const double *values) = 0;
    // In place: b (equation order) in, x (coordinate order) out.
    virtual void solve(double *x) = 0;
    // In place: b (coordinate order) in, x (equation order) out.
    virtual void solve_transposed(double *x) = 0;
    virtual const char *name() const = 0;
    // Factorisations of a group block that left its planned pivot order for partial pivoting,
    // since this solver was made (0 for solvers without a plan). A normal path should take none:
    // the fallback repairs even a garbled block, so only this count (and the time) shows it.
    virtual long fallbacks() const { return 0; }
};

enum class LinearSolverKind { Automatic, Dense, Block };

// Block: the bordered-block LU with the lane kernels lane_kernels_for chooses (lane_lu.hpp).
std::unique_ptr<LinearSolver> make_linear_solver(const Mechanism &m, LinearSolverKind kind);

struct LaneKernels;
// The bordered-block LU with the given lane kernels, or one group at a time if null (tests and
// benchmarks compare them); null if the mechanism has no block structure.
std::unique_ptr<LinearSolver> make_block_solver(const Mechanism &m, const LaneKernels *lanes);

}  // namespace mbs
