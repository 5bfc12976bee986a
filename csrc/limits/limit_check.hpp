// The limits a controller checks at a pose (stewart/stewart_limits.h): stroke, joint angles, leg
// interference, condition number; each class's smallest margin and where it is.
#pragma once

#include <Eigen/Dense>

#include "kinematics/closed_form.hpp"
#include "kinematics/frames.hpp"
#include "stewart/stewart_limits.h"

namespace stewart {

// Everything the check needs from the parameters, per leg so that any geometry fits.
struct LimitConstants {
    PlatformGeometry geometry;  // joint centres, characteristic length (the Jacobian's)
    Frames frames;              // poses checked are the tool frame's in the user frame
    Matrix36 base_neutral;      // unit neutral axes, base frame
    Matrix36 platform_neutral;  // unit neutral axes, platform frame
    double stroke_min[STEWART_LEGS], stroke_max[STEWART_LEGS];
    double base_joint_limit[STEWART_LEGS], platform_joint_limit[STEWART_LEGS];
    bool uniform_base_limit, uniform_platform_limit;  // one joint limit for all legs
    double leg_diameter;
    // Legs as actuators (leg_body_length or leg_rod_length > 0): a body of radius body_radius
    // from the base joint over body_length and a rod of radius rod_radius from the platform
    // joint over rod_length, each cut to the leg; else (shaped false) a cylinder of diameter
    // leg_diameter from joint to joint.
    bool shaped;
    double body_radius, body_length, rod_radius, rod_length;
    // The largest sum of two parts' radii (leg_diameter unshaped): a pair whose joint-to-joint
    // segments are farther apart than this cannot interfere; 0: no interference check.
    double interference_reach;
    // Legs that share a joint (a 3-6 platform's pairs) meet there by design: never checked.
    bool shares_joint[STEWART_LEGS][STEWART_LEGS];
    // Software position limits of the tool pose in the user frame (-DBL_MAX / DBL_MAX: none).
    double axis_min[6], axis_max[6];
    double warn_condition;
    // The leg classes' limits (speed, acceleration, jerk, force; class STEWART_LIMIT_LEG_SPEED
    // + i), per leg, +inf where the parameter is 0 (none).
    double leg_limit[4][STEWART_LEGS];
    double shortest_stroke_min;  // min_k stroke_min[k]: the shortest leg within the stroke
    double longest_arm;          // max_k |b_k - tool origin|: the fastest platform joint per
                                 // rad of a tool angle [m]
    double platform_radius;      // max_k |b_k|, platform frame [m]
    // A leg whose cosine to its neutral axis is at least this is inside its joint limit for sure
    // (platform_limit_failures skips its arc): cos(limit) + kJointCosineSlack, -inf for limits
    // >= pi, +inf (never skipped) for limits <= 0.
    double base_inside_cosine[STEWART_LEGS], platform_inside_cosine[STEWART_LEGS];
};

// The constants of the parameters' limits with condition limit warn_condition. A zero neutral
// axis becomes the leg's direction at home (0, 0, home_height, 0, 0, 0).
LimitConstants limit_constants(const stewart_params &p, const PlatformGeometry &geometry,
                               double warn_condition);

// The margins of every geometric class at the platform's pose q (base frame; finite), as
// stewart_limits_output (the leg classes' +inf); never NaN. Without the condition
// (with_condition false: its margin +inf, condition 0) for searches that know it is within its
// limit; else ||J^-T||_inf into *inverse_norm if given (+inf if singular). every_leg: each leg's
// margins into out.leg_margin too (else it is not written; the searches need the smallest).
void check_platform_limits(const LimitConstants &c, const double q[6], stewart_limits_output &out,
                           bool with_condition = true, double *inverse_norm = nullptr,
                           bool every_leg = false);
// The failing bits (stewart_limits_output.failed) of the joint classes and of interference at
// the platform's pose q: those of check_platform_limits(c, q, out, false), found without the
// margins (the plant's warnings); interference's may differ at rounding distance from the
// diameter (a pair is measured only where its sphere gap leaves doubt).
int platform_limit_failures(const LimitConstants &c, const double q[6]);
// The same at the platform's position and rotation (base frame; the plant's state, whose
// rotation is its quaternion's): the verdicts at q's rotation except at rounding distance from
// a limit (the two rotations differ by a few roundings).
int platform_limit_failures(const LimitConstants &c, const Eigen::Vector3d &position,
                            const Eigen::Matrix3d &rotation);
// How far the verdicts of the last exact platform_limit_failures without failures were from
// changing, and where: the pose (base frame) and, from it, the smallest cosine above a joint's
// inside cosine, the smallest leg-pair distance (or sphere gap) above the diameter, the
// shortest leg. A pose whose legs moved less than these allow has no failure either.
struct LimitClearance {
    bool valid = false;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    double joint_cosine = 0;  // min over legs and joints of cosine - inside cosine
    double interference = 0;  // min over pairs of the distance (or sphere gap) - diameter [m]
    double shortest_leg = 0;  // min_k length [m]
};
// Whether `clearance` proves that the exact check at the platform's position and rotation finds
// nothing (the bound in limit_check.cpp): platform_limit_failures' test before it checks.
bool clearance_spares(const LimitConstants &c, const LimitClearance &clearance,
                      const Eigen::Vector3d &position, const Eigen::Matrix3d &rotation);
// platform_limit_failures(c, position, rotation), the same verdicts, and without the legs where
// `clearance` (its last exact run's, kept by the caller) proves that nothing fails: no leg's
// platform joint has moved further than every limit's clearance allows (the bound in
// limit_check.cpp). Updates clearance where it runs the check.
int platform_limit_failures(const LimitConstants &c, const Eigen::Vector3d &position,
                            const Eigen::Matrix3d &rotation, LimitClearance &clearance);
// The same at the tool frame's pose q in the user frame (the API's poses), with every leg's
// margins (out.leg_margin) and the axis class.
void check_limits(const LimitConstants &c, const double q[6], stewart_limits_output &out,
                  bool with_condition = true, double *inverse_norm = nullptr);

// The leg classes (speed, acceleration, jerk, force) of the input's derivatives and forces
// into out (margin, leg, leg_margin; +inf where not given or no limit), then first and failed
// again. Errors as stewart_limits_check's for the derivatives (leg_limits.cpp).
stewart_status check_leg_limits(const LimitConstants &c, const stewart_limits_input &in,
                                stewart_limits_output &out, char *msg, size_t size);

// `first` (the failing class of lowest number, or none) and `failed` (a bit per failing class)
// from the margins: every class fails below 0, interference also at 0 (legs that touch) when it
// is checked at all.
void classify_margins(const LimitConstants &c, stewart_limits_output &out);

// The interference margin of legs i and j from their base joints, platform joints (world),
// unit axes and lengths: the shortest distance between their parts less the parts' radii
// (+inf for legs that share a joint).
double leg_pair_margin(const LimitConstants &c, int i, int j, const Matrix36 &top,
                       const Matrix36 &axis, const Vector6 &length);

// The software position limits' margin at the tool pose q (user frame): min(q_i - axis_min[i],
// axis_max[i] - q_i) of the axis nearest its limit, in that axis' unit [m or rad], and the axis
// (1..6) in *axis; an angle's margin times longest_arm ranks it among the positions'.
double axis_limit_margin(const LimitConstants &c, const double q[6], int *axis);

// STEWART_OK, or STEWART_ERR_PARAMETER naming the parameter and its value: a neutral axis that
// is not zero but too small to have a direction (largest component subnormal); axis_min[i] >
// axis_max[i]; two joints of one side (not one shared point) closer than the legs are thick
// there, which would interfere at every pose (the legs and the distance named). Per-element
// ranges (finite values) are checked before.
stewart_status check_limit_parameters(const stewart_params &p, char *msg, size_t size);

// The squared shortest distance between segments [p0, p1] and [q0, q1] (any, also degenerate
// or parallel), and the legs' check on it.
double segment_distance_squared(const Eigen::Vector3d &p0, const Eigen::Vector3d &p1,
                                const Eigen::Vector3d &q0, const Eigen::Vector3d &q1);

}  // namespace stewart
