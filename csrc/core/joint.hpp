// Joints (and every other constraint: fixed body, normalisation, drivers) as table-driven types.
// Each type knows its number of equations and fills, for its rows, the residual Phi, the Jacobian
// blocks for its two bodies (row-major n x 7, coordinates r then p), Phi_t and gamma (the right
// side of Phi_q q_ddot = gamma). Adding a type: one file in joints/ and one entry in joint_table.
#pragma once

#include "core/euler.hpp"
#include "mbs/mbs.h"

namespace mbs {

enum class JointType {
    FixedBody,         // 7: q_i = q_fixed
    Normalization,     // 1: p_i.p_i - 1
    Spherical,         // 3: points coincide
    Cardan,            // 4: points coincide, cross arms perpendicular
    Cylindrical,       // 4: axes parallel and collinear
    Revolute,          // 5: points coincide, axes parallel
    Prismatic,         // 5: cylindrical, and no rotation about the axis
    Weld,              // 6: points coincide, frames aligned
    CoordinateDriver,  // 1: q_i[c] = f(t)
    PoseDriver,        // 7: q_i = f(t) (position and Euler parameters)
    DistanceDriver,    // 1: distance along a cylindrical/prismatic axis = f(t)
    AngleDriver,       // 1: rotation angle of a revolute joint = f(t)
    Count
};

// A driver's prescribed function at the time of the solve.
struct DriverValue {
    double value = 0, rate = 0, accel = 0;
};

struct JointDef {
    JointType type = JointType::FixedBody;
    int body_i = -1, body_j = -1;                         // body_j = -1 for one-body constraints
    Vec3 point_i = Vec3::Zero(), point_j = Vec3::Zero();  // attachment points, body frames
    // Per type: Cardan arm in [0]; cylindrical/revolute/prismatic: [0], [1] perpendicular to the
    // axis [2] on body i, axis in [2] and (prismatic) a perpendicular in [0] on body j;
    // weld: the frame of each body; drivers: copied from the joint they drive.
    Vec3 axis_i[3] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
    Vec3 axis_j[3] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
    int coordinate = 0;                         // coordinate driver: 0..6 of body i
    int driver = -1;                            // first driver slot, -1 if not a driver
    double q_fixed[7] = {0, 0, 0, 1, 0, 0, 0};  // fixed body
};

// A body's rotation and the matrices of its derivatives, formed once per joint evaluation:
// A u, d(A u)/dt = rate u, velocity-quadratic part of d2(A u)/dt2 = quad u.
struct BodyFrame {
    Mat3 A, rate, quad;
};

struct JointInput {
    const JointDef &def;
    const double *q_i, *q_j;             // 7 coordinates of each body (q_j null for one body)
    const double *v_i, *v_j;             // their velocities; null unless gamma is asked for
    const DriverValue *drive;            // the joint's driver slots, null if none
    const BodyFrame *frame_i, *frame_j;  // two-body joints only; rate and quad only with v
};

// Any pointer may be null: that output is not wanted.
struct JointOutput {
    double *phi, *jac_i, *jac_j, *phi_t, *gamma;
};

using JointEvaluate = void (*)(const JointInput &, const JointOutput &);

struct JointTypeInfo {
    const char *name;
    int equations;
    int drivers;  // driver slots it reads
    int bodies;   // 1 or 2
    JointEvaluate evaluate;
};

const JointTypeInfo &joint_type(JointType t);

// A cylindrical joint and a distance driver of it (the same two bodies and points) in one call:
// the driver's row takes the joint's separation, and each axis is turned into the world once.
// Every row is the separate calls' products in their order (the same bits).
void evaluate_cylindrical_with_distance(const JointInput &joint, const JointOutput &joint_out,
                                        const JointInput &driver, const JointOutput &driver_out);

}  // namespace mbs
