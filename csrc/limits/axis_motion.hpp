// One axis of a pose moved with the other five held (the axis ranges of stewart_limits.h): the
// platform then moves rigidly, along a fixed world direction or about a fixed world axis, so
// each joint's path and speed, and each leg's length along the path, are known in closed form.
#pragma once

#include <Eigen/Dense>

#include "limits/limit_check.hpp"

namespace stewart {

// The platform's motion as axis `axis` of the tool pose q (in the user frame) moves by t >= 0
// toward sign: a translation along `direction`, or a turn by the angle t about `direction`
// through `centre` (the tool origin): a change of one of roll, pitch, yaw turns the platform about
// a fixed world axis (yaw: the user's z; pitch: Rz(yaw) y; roll: Rz(yaw) Ry(pitch) x).
struct AxisMotion {
    bool rotation;
    Eigen::Vector3d direction;  // unit, world (base frame)
    Eigen::Vector3d centre;     // on the rotation axis, world [m]
};
AxisMotion axis_motion(const Frames &frames, const double q[6], int axis, double sign);

// The legs at one platform pose (base frame), computed as check_platform_limits does.
struct LegState {
    Eigen::Matrix3d rotation;  // platform to world
    LegKinematics kinematics;  // arms R b_k, unit leg vectors, lengths (rates unused)
    Matrix36 top;              // platform joint centres, world [m]
    bool has_direction;        // every leg longer than the geometry's min_length
};
// The legs at the platform pose `platform` (x, y, z, roll, pitch, yaw; base frame).
void leg_state(const LimitConstants &c, const double platform[6], LegState &out);

// How fast point x (world, moving with the platform) moves per unit t.
Eigen::Vector3d point_velocity(const AxisMotion &m, const Eigen::Vector3d &x);

// The most point x can move per unit t anywhere along the motion (1 for a translation, its
// distance from the axis for a turn: constant along it).
double point_speed(const AxisMotion &m, const Eigen::Vector3d &x);

// The first t in [0, extent] at which some leg's length reaches its stroke_min or stroke_max
// along the motion from `legs` (every leg within its stroke there), and that leg (1..6), or
// extent and leg 0 if none does. Exact: L_k^2(t) is t^2 + 2 b t + L_k^2 for a translation and
// A + B cos t + C sin t for a turn, whose roots are closed forms.
double first_stroke_end(const LimitConstants &c, const LegState &legs, const AxisMotion &m,
                        double extent, int &leg);

}  // namespace stewart
