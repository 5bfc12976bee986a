// Assembly walks the joint list: residual, Jacobian values (in the mechanism's pattern order),
// Phi_t and gamma of the whole system.
#pragma once

#include "core/mechanism.hpp"

namespace mbs {

void assemble_residual(const Mechanism &m, const double *q, const DriverValue *drv, double *phi);
void assemble_jacobian(const Mechanism &m, const double *q, const DriverValue *drv, double *values);
// Both in one pass (they share most of the work).
void assemble_residual_and_jacobian(const Mechanism &m, const double *q, const DriverValue *drv,
                                    double *phi, double *values);
void assemble_phi_t(const Mechanism &m, const double *q, const DriverValue *drv, double *phi_t);
void assemble_gamma(const Mechanism &m, const double *q, const double *q_dot,
                    const DriverValue *drv, double *gamma);

// One joint alone (its rows only), for tests and reactions.
void evaluate_joint(const Mechanism &m, int joint, const double *q, const double *q_dot,
                    const DriverValue *drv, const JointOutput &out);

}  // namespace mbs
