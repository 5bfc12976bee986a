// The forward position problem L(q) = L_measured in the six pose coordinates, solved by KINSOL's
// Newton iteration with the analytic Jacobian behind a custom 6 x 6 SUNMatrix/SUNLinearSolver
// (LU with partial pivoting; no finite differences).
#pragma once

#include "kinematics/closed_form.hpp"

namespace stewart {

// The legs at one pose: what the residual computes and the Jacobian (and the caller, at the
// solution) reuse.
struct LegsAt {
    bool valid = false;
    double q[6];
    Eigen::Matrix3d rotation;
    Matrix36 arm, axis;  // R b_k and the unit leg axis n_k, world
    Vector6 length, residual;
};

struct NewtonStats {
    int iterations = 0;     // KINSOL nonlinear iterations
    double residual = 0;    // max-norm of L(q) - L_measured at the last iterate [m]
    int worst_leg = 0;      // leg (0-based) with the largest |residual| there
    int flag = 0;           // KINSOL's return flag
};

class ForwardNewton {
public:
    // Allocates the KINSOL objects once; check ok().
    ForwardNewton();
    ~ForwardNewton();
    ForwardNewton(const ForwardNewton &) = delete;
    ForwardNewton &operator=(const ForwardNewton &) = delete;
    bool ok() const { return impl_ != nullptr && ok_; }

    // Newton from q (overwritten with the last iterate) toward L(q) = target. STEWART_OK when the
    // residual max-norm is <= tolerance; STEWART_ERR_NOT_CONVERGED (or STEWART_ERR_SINGULAR when
    // the Jacobian could not be factored) with a message otherwise. Allocates nothing.
    stewart_status solve(const PlatformGeometry &g, const double target[STEWART_LEGS],
                         double tolerance, int max_iterations, double q[6], NewtonStats &stats,
                         char *msg, size_t size);

    // The legs at the last iterate of the last solve.
    const LegsAt &last() const;

    struct Impl;

private:
    Impl *impl_ = nullptr;
    bool ok_ = false;
};

}  // namespace stewart
