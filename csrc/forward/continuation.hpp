// Proven steps along a path of lengths (Kantorovich): which pose a small change of the six
// lengths leads to, and the pose reached from home along the straight path of lengths.
#pragma once

#include "forward/leg_factors.hpp"
#include "forward/newton.hpp"

namespace stewart {

// Around a pose x0 whose lengths are L0 (to the tolerance): any lengths L1 with
// |L1 - L0|_inf <= max_change have exactly one pose within `radius` of x0 (distance as
// pose_distance), and the straight path of lengths from L0 to L1 leads to it without leaving
// that ball. From Kantorovich's theorem with beta = |J^-1|_inf at x0 and a Lipschitz bound
// gamma on J over the ball (the legs' lengths, the arms' and the platform's size).
struct ProvenStep {
    double max_change = 0;  // [m]
    double radius = 0;      // [m, the rotation as platform radius times angle]
};
// inverse_norm1: |J^-1|_1 at x0; shortest: its shortest leg; arm: the largest |b_k| / r_t.
ProvenStep proven_step(const PlatformGeometry &g, double inverse_norm1, double shortest, double arm,
                       double tolerance);
// The largest |b_k| / r_t of the geometry.
double largest_arm(const PlatformGeometry &g);

// The distance of two poses in the metric of ProvenStep: max(|p_a - p_b|_inf, r_t angle(R_a R_b^T)).
double pose_distance(const PlatformGeometry &g, const double a[6], const double b[6]);

// The pose reached from `start` (whose lengths are start_lengths) along the straight path of
// lengths to `target`, in steps Newton takes in a few iterations with the determinant's sign kept
// (a step is halved until it does; the solve's max_iterations does not apply); q holds it. False
// when the path meets a singular pose or its steps shrink below 1/65536 of the way (the message
// says so; q then undefined). newton is a workspace (its last legs are q's).
bool continue_lengths(const PlatformGeometry &g, ForwardNewton &newton, const double start[6],
                      const double start_lengths[6], const double target[6], double tolerance,
                      double q[6], int &steps, char *msg, size_t size);

}  // namespace stewart
