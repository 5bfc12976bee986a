// The mutable data of one mechanism run: state, driver values, statistics and every workspace a
// step needs (allocated here, once). Copying it (copy_state) is a rollback point.
#pragma once

#include <memory>
#include <vector>

#include "core/linear_solver.hpp"
#include "mbs/mbs.h"

namespace mbs {

class PositionSolver;

struct SolverOptions {
    double tolerance = MBS_DEFAULT_TOLERANCE;  // max-norm of the residual
    int max_iterations = MBS_DEFAULT_MAX_ITERATIONS;
    bool modified_newton = false;  // keep the Jacobian across Newton iterations
    LinearSolverKind linear = LinearSolverKind::Automatic;
    bool kinsol_dense = false;  // KINSOL's own dense matrix and solver (a baseline)
};

struct SolveStats {
    int iterations = 0;
    double residual = 0;
};

struct State {
    // Allocates every workspace; ok() false (message says why) if that failed.
    State(const Mechanism &m, const SolverOptions &kind = SolverOptions());
    bool ok() const { return newton != nullptr && linear != nullptr; }
    ~State();
    State(const State &) = delete;
    State &operator=(const State &) = delete;

    const Mechanism &mechanism;
    std::vector<double> q, q_dot, q_ddot, lambda;
    std::vector<DriverValue> drive;
    double time = 0;
    bool has_history = false;  // q, q_dot, q_ddot hold the solution at `time`
    SolveStats stats;
    char message[MBS_MESSAGE_SIZE] = "";

    // Workspaces.
    std::vector<double> values;
    // A state being loaded (load_state), checked here before it replaces the current one.
    std::vector<double> load_q, load_phi;
    std::vector<DriverValue> load_drive;
    std::unique_ptr<LinearSolver> linear;
    bool factor_current = false;  // linear holds the factorisation at q
    bool values_current = false;  // values hold Phi_q at q
    std::unique_ptr<PositionSolver> newton;
    SolverOptions newton_options;  // the options the Newton solver is configured with
};

// Copies the state (not the workspaces) of src into dst, both of the same mechanism.
void copy_state(State &dst, const State &src);
// The state copy_state copies, as bytes: a tag, the sizes, then the values (same machine).
size_t saved_state_size(const State &s);
void save_state(const State &s, unsigned char *out);
// False (s unchanged, msg says why) unless the bytes are a saved state of a mechanism of s's
// shape that fits s's mechanism: every value finite, fixed bodies at their placement, Euler
// parameters of the other bodies unit (|p.p - 1| <= kLoadNormalization), and, for a solved state,
// the constraint residual no larger than the state records (twice, plus a few roundings).
bool load_state(State &s, const unsigned char *in, size_t size, char *msg, size_t msg_size);
constexpr double kLoadNormalization = 1e-6;
// Forgets the history: the next position solve starts from q as it is.
void reset_history(State &s);
// Forgets the history and puts every body back at its reference configuration: as new.
void reset(State &s);

}  // namespace mbs
