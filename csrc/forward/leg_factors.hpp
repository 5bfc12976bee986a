// The legs at a pose and the leg Jacobian there, factored once: what the forward Newton step,
// the condition number, the assembly-mode sign and the pose rates all solve with.
#pragma once

#include "kinematics/closed_form.hpp"

namespace stewart {

// Six leg vectors (world), component-major: c[i][k] is component i of leg k (the legs two at a
// time).
struct LegVectors {
    double c[3][STEWART_LEGS];
};

// The legs at one pose: what the residual computes and the Jacobian (and the caller, at the
// solution) reuse.
struct LegsAt {
    bool valid = false;
    double q[6];
    double cos_roll, sin_roll, cos_pitch, sin_pitch, cos_yaw, sin_yaw;
    Eigen::Matrix3d rotation;
    // R b_k and the unit leg axis n_k, world, component-major (arm[i][k]: the legs two at a time).
    double arm[3][STEWART_LEGS], axis[3][STEWART_LEGS];
    Vector6 length, residual;
};

// The legs at pose q and the residual L(q) - target, into c.
void evaluate_legs(const PlatformGeometry &g, const double q[6], const double target[6], LegsAt &c);

// LU (partial pivoting, row-major) of the leg Jacobian J, row k = (n_k, (R b_k x n_k) / c): the
// leg rates from the twist (v, c omega); with the pitch and yaw where it was taken, which map the
// angular velocity to angle rates.
struct PitchYawTrig {
    double cos_pitch, sin_pitch, cos_yaw, sin_yaw;
};
struct LegFactors {
    double lu[36];
    int pivot[6];  // row k swapped with row pivot[k] at step k
    int order[6];  // the rows' order after all swaps: (P b)_i = b_order[i]
    PitchYawTrig trig;
    double scale;  // c, the platform's characteristic length [m]
};

// J at the legs `at` factored into f; its 1-norm into norm1. False if J is singular (a pivot
// below 1e-14 of its largest entry) or not finite.
bool factor_legs(const PlatformGeometry &g, const LegsAt &at, LegFactors &f, double &norm1);

// Pose-coordinate rates (x, y, z, roll, pitch, yaw) whose leg rates are v: the twist J^-1 v,
// its angular velocity to angle rates at the pitch and yaw of `at` (kinematics/motion.hpp
// angle_rates_of). False at pitch = +-90 deg (out undefined).
bool pose_rates_from(const LegFactors &f, const PitchYawTrig &at, const double v[6], double out[6]);

// The 1-norm of J^-1 (its largest column sum): cond_1(J) = norm1 * this.
double inverse_norm1(const LegFactors &f);

// Sign of det J from the factors: +1 or -1.
int determinant_sign(const LegFactors &f);

// False (message-free) unless every value is finite, every pivot in range and U's diagonal
// non-zero: factors read from bytes are checked with it. Sets the order from the pivots.
bool factors_usable(LegFactors &f);

}  // namespace stewart
