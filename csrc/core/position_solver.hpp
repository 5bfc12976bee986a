// The position problem Phi(q, t) = 0, solved by KINSOL's Newton iteration with our structured
// linear solver plugged in (a custom SUNMatrix holding the Jacobian values in the mechanism's
// pattern, and a custom SUNLinearSolver factoring them), or KINSOL's dense one as a baseline.
#pragma once

#include "core/state.hpp"

namespace mbs {

class PositionSolver {
public:
    // Allocates everything; check ok() (message in state.message otherwise).
    PositionSolver(State &state, const SolverOptions &options);
    ~PositionSolver();
    PositionSolver(const PositionSolver &) = delete;
    PositionSolver &operator=(const PositionSolver &) = delete;
    bool ok() const { return ok_; }

    // Solves from state.q (the initial guess) at the driver values in state.drive; q is
    // overwritten with the solution. Fills state.stats.
    mbs_status solve(const SolverOptions &options);

    struct Impl;

private:
    Impl *impl_;
    bool ok_ = false;
};

}  // namespace mbs
