// The forward position problem L(q) = L_measured in the six pose coordinates, solved by KINSOL's
// Newton iteration with the analytic Jacobian behind a custom 6 x 6 SUNMatrix/SUNLinearSolver
// (the leg Jacobian's LU with partial pivoting; no finite differences). Tracking, the Jacobian
// factored at the last solution is KINSOL's for the first iteration (a chord step: no set-up).
#pragma once

#include "forward/leg_factors.hpp"

namespace stewart {

struct NewtonStats {
    int iterations = 0;   // KINSOL nonlinear iterations
    double residual = 0;  // max-norm of L(q) - L_measured at the last iterate [m]
    int worst_leg = 0;    // leg (0-based) with the largest |residual| there
    int flag = 0;         // KINSOL's return flag
};

class ForwardNewton {
public:
    // Allocates the KINSOL objects once and sets them up for every solve; check ok().
    ForwardNewton();
    ~ForwardNewton();
    ForwardNewton(const ForwardNewton &) = delete;
    ForwardNewton &operator=(const ForwardNewton &) = delete;
    bool ok() const { return impl_ != nullptr && ok_; }

    // Newton from q (overwritten with the last iterate) toward L(q) = target. chord: factors of
    // the leg Jacobian at a pose `drift` away from q (max of |translation| / c and |angle|
    // differences; the last solution's), taken for the first iteration when one chord step is
    // expected to converge (residual at q times drift <= tolerance: the step's error is about
    // the residual times the Jacobian's relative change), or null (factored at q). STEWART_OK when the residual max-norm is <= tolerance; STEWART_ERR_NOT_CONVERGED (or
    // STEWART_ERR_SINGULAR when the Jacobian could not be factored) with a message otherwise.
    // Allocates nothing.
    stewart_status solve(const PlatformGeometry &g, const double target[STEWART_LEGS],
                         double tolerance, int max_iterations, const LegFactors *chord,
                         double drift, double q[6], NewtonStats &stats, char *msg, size_t size);

    // The legs at the last iterate of the last solve.
    const LegsAt &last() const;

    struct Impl;

private:
    Impl *impl_ = nullptr;
    bool ok_ = false;
};

}  // namespace stewart
