// stewart_plant_derivatives: the plant's equations of motion as a right-hand side in the pose
// coordinates (x, y, z, roll, pitch, yaw and their rates: the tool's in the user frame, as every
// pose the plant takes and gives), for masters that integrate the state themselves (the Model
// Exchange FMU). The twist rate comes from the same equations the plant's integrator uses
// (plant_equations.cpp); only the changes of coordinates are here.
#include <cmath>
#include <cstring>

#include "kinematics/frames.hpp"
#include "kinematics/motion.hpp"
#include "kinematics/pose_names.hpp"
#include "plant/plant_object.hpp"
#include "util/create.hpp"
#include "util/message.hpp"

using stewart::set_message;
namespace plant = stewart::plant;

namespace {

const char *fault_text(plant::LegFault f) {
    switch (f) {
        case plant::LegFault::ZeroLength: return "has zero length";
        case plant::LegFault::LockedBaseCardan:
            return "lies along its base Cardan's arm (locked Cardan)";
        case plant::LegFault::LockedPlatformCardan:
            return "lies along its platform Cardan's arm (locked Cardan)";
        case plant::LegFault::None: break;
    }
    return "is undefined";
}

// Length, rate and acceleration of every leg for the platform motion m (accelerations included);
// bit k of the result set when leg k+1 is outside [stroke_min, stroke_max].
int leg_motion(const stewart_plant &p, const stewart::Motion &m, stewart_lengths &out) {
    const stewart_params &par = p.model->params;
    int stroke_legs = 0;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const plant::Vec3 arm = m.rotation * p.dynamics.legs.platform_points.col(k);
        const plant::Vec3 d = m.position + arm - p.dynamics.legs.base_points.col(k);
        const plant::Vec3 d_dot = m.velocity + m.omega.cross(arm);
        const plant::Vec3 d_ddot =
            m.acceleration + m.alpha.cross(arm) + m.omega.cross(m.omega.cross(arm));
        const double length = d.norm(), rate = d.dot(d_dot) / length;
        out.length[k] = length;
        out.length_rate[k] = rate;
        // d/dt (d . d_dot / L) = (|d_dot|^2 + d . d_ddot - L_dot^2) / L
        out.length_accel[k] = (d_dot.squaredNorm() + d.dot(d_ddot) - rate * rate) / length;
        if (length < par.stroke_min[k] || length > par.stroke_max[k]) stroke_legs |= 1 << k;
    }
    return stroke_legs;
}

// STEWART_OK, or STEWART_ERR_ARGUMENT naming the first non-finite state component or force.
stewart_status check_input(const stewart_plant_derivative_input &in, char *msg, size_t size) {
    for (int i = 0; i < 6; ++i) {
        if (!std::isfinite(in.pose.q[i]))
            return set_message(msg, size, STEWART_ERR_ARGUMENT, "%s = %g must be finite",
                               stewart::kPoseNames[i], in.pose.q[i]);
        if (!std::isfinite(in.pose.q_dot[i]))
            return set_message(msg, size, STEWART_ERR_ARGUMENT, "%s_dot = %g must be finite",
                               stewart::kPoseNames[i], in.pose.q_dot[i]);
    }
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (!std::isfinite(in.force[k]))
            return set_message(msg, size, STEWART_ERR_ARGUMENT, "F[%d] = %g must be finite", k + 1,
                               in.force[k]);
    if (!std::isfinite(in.time))
        return set_message(msg, size, STEWART_ERR_ARGUMENT, "time = %g must be finite", in.time);
    return STEWART_OK;
}

// The platform's pose in the base frame (the tool's in the user frame is given), with zero
// angle accelerations: the motion's alpha is then E_dot * angle rates alone.
stewart_status platform_pose_of(const stewart_plant &p, const stewart_pose &given,
                                stewart_pose &pose, char *msg, size_t size) {
    const stewart::Frames &frames = p.model->frames;
    if (frames.identity) {
        pose = given;
    } else if (!stewart::platform_pose(frames, given.q, given.q_dot, pose.q, pose.q_dot,
                                       plant::kMinCosPitch)) {
        return set_message(msg, size, STEWART_ERR_SINGULAR,
                           "this tool pose puts the platform's pitch at +-90 degrees (tool_frame, "
                           "user_frame), where its roll and yaw rates are undefined");
    }
    for (int i = 0; i < 6; ++i)
        if (!std::isfinite(pose.q[i]) || !std::isfinite(pose.q_dot[i]))
            return set_message(msg, size, STEWART_ERR_ARGUMENT,
                               "%s = %g, %s_dot = %g are out of range: the platform's pose or "
                               "rates they give (tool and user frames) overflow",
                               stewart::kPoseNames[i], given.q[i], stewart::kPoseNames[i],
                               given.q_dot[i]);
    for (double &a : pose.q_ddot) a = 0;
    return STEWART_OK;
}

// The plant's equations at the platform motion m (of pose) under the forces, into e; refused
// naming the leg without a direction (or along a Cardan's arm) and the pose there.
stewart_status evaluate(const stewart_plant &p, const stewart::Motion &m, const double *force,
                        const stewart_pose &pose, plant::Evaluation &e, char *msg, size_t size) {
    if (plant::twist_rate(p.dynamics, m, force, e)) return STEWART_OK;
    const int k = e.fault_leg;
    const plant::Vec3 d = m.position + m.rotation * p.dynamics.legs.platform_points.col(k) -
                          p.dynamics.legs.base_points.col(k);
    return set_message(msg, size,
                       e.fault == plant::LegFault::ZeroLength ? STEWART_ERR_UNREACHABLE
                                                              : STEWART_ERR_SINGULAR,
                       "leg %d %s at x, y, z = %g, %g, %g m, roll, pitch, yaw = %g, %g, %g "
                       "rad (L[%d] = %g m)",
                       k + 1, fault_text(e.fault), pose.q[0], pose.q[1], pose.q[2], pose.q[3],
                       pose.q[4], pose.q[5], k + 1, d.norm());
}

// The platform's accelerations from the evaluation e: into m (its twist rate) and pose.q_ddot
// (the angles' second derivatives), and the base wrench of the bodies' motions into o.
void platform_accelerations(const stewart_plant &p, const plant::Evaluation &e, stewart_pose &pose,
                            stewart::Motion &m, stewart_plant_output &o) {
    // alpha = E angles_ddot + E_dot angles_dot, so angles_ddot = E^-1 (alpha - E_dot angles_dot).
    const double pitch = pose.q[4];
    const plant::Vec3 alpha = e.twist_rate.tail<3>();
    const plant::Mat3 E = stewart::angle_rate_matrix(std::cos(pitch), std::sin(pitch),
                                                     std::cos(pose.q[5]), std::sin(pose.q[5]));
    const plant::Vec3 angle_accel = E.partialPivLu().solve(alpha - m.alpha);
    m.acceleration = e.twist_rate.head<3>();
    m.alpha = alpha;

    stewart::Motion bodies[STEWART_PLANT_BODIES];
    plant::body_motions(p.dynamics, m, e, bodies);
    plant::Vec3 force, torque;
    plant::base_wrench(p.dynamics, bodies, force, torque);
    for (int i = 0; i < 3; ++i) {
        pose.q_ddot[i] = m.acceleration[i];
        pose.q_ddot[3 + i] = angle_accel[i];
        o.base_force[i] = force[i];
        o.base_torque[i] = torque[i];
    }
}

// STEWART_OK, or STEWART_ERR_ARGUMENT when a derivative or output overflowed.
stewart_status check_outputs_finite(const stewart_plant_output &o, const double *force,
                                    const stewart_pose &pose, char *msg, size_t size) {
    const double *values[6] = {o.pose.q_ddot,          o.lengths.length, o.lengths.length_rate,
                               o.lengths.length_accel, o.base_force,     o.base_torque};
    const int counts[6] = {6, STEWART_LEGS, STEWART_LEGS, STEWART_LEGS, 3, 3};
    for (int g = 0; g < 6; ++g)
        for (int i = 0; i < counts[g]; ++i)
            if (!std::isfinite(values[g][i]))
                return set_message(msg, size, STEWART_ERR_ARGUMENT,
                                   "the state or forces are out of range: the derivatives or "
                                   "outputs overflow (F[1] = %g N, x_dot = %g m/s)",
                                   force[0], pose.q_dot[0]);
    return STEWART_OK;
}

}  // namespace

extern "C" stewart_status stewart_plant_derivatives(stewart_plant *p,
                                                    const stewart_plant_derivative_input *in,
                                                    stewart_plant_output *out) {
    stewart_status s = stewart::call_arguments_ok(p, in, out, "argument");
    if (s != STEWART_OK) return s;
    char *msg = p->message;
    const size_t size = sizeof p->message;
    if (p->dynamics.drives.inductive)
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "voltage input with winding_inductance > 0: the windings' currents "
                           "are states this call does not take (stewart_plant_step integrates "
                           "them; or set the inductances to 0)");
    if ((s = check_input(*in, msg, size)) != STEWART_OK) return s;
    if (!(std::fabs(std::cos(in->pose.q[4])) > plant::kMinCosPitch))
        return set_message(msg, size, STEWART_ERR_SINGULAR,
                           "pitch = %.17g rad is at +-90 degrees, where roll and yaw rates are "
                           "undefined",
                           in->pose.q[4]);
    stewart_pose pose{};
    if ((s = platform_pose_of(*p, in->pose, pose, msg, size)) != STEWART_OK) return s;
    stewart::Motion m = stewart::motion_of_pose(pose);
    if (!m.omega.allFinite())
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "roll_dot, pitch_dot, yaw_dot = %g, %g, %g rad/s overflow the angular "
                           "velocity",
                           pose.q_dot[3], pose.q_dot[4], pose.q_dot[5]);
    plant::Evaluation e;
    if ((s = evaluate(*p, m, in->force, pose, e, msg, size)) != STEWART_OK) return s;
    stewart_plant_output o{};
    o.time = in->time;
    platform_accelerations(*p, e, pose, m, o);
    const stewart::Frames &frames = p->model->frames;
    stewart::base_wrench_to_given_frame(frames, o.base_force, o.base_torque);
    // The state given is the state returned (no other branch of roll and yaw); its accelerations
    // are the tool's in the user frame.
    o.pose = in->pose;
    stewart_pose tool = pose;
    if (!frames.identity && !stewart::tool_pose(frames, pose, 2, tool, plant::kMinCosPitch))
        return set_message(msg, size, STEWART_ERR_SINGULAR,
                           "pitch = %.17g rad is at +-90 degrees, where roll and yaw rates are "
                           "undefined",
                           in->pose.q[4]);
    std::memcpy(o.pose.q_ddot, tool.q_ddot, sizeof o.pose.q_ddot);
    o.stroke_legs = leg_motion(*p, m, o.lengths);
    if (p->model->length_offsets)  // the sensors read Cardan-to-Cardan length - offset
        for (int k = 0; k < STEWART_LEGS; ++k)
            o.lengths.length[k] -= p->model->params.length_offset[k];
    o.warnings = o.stroke_legs ? STEWART_WARN_STROKE : 0;
    plant_drive_outputs(*p, in->force, e, o);
    if ((s = check_outputs_finite(o, in->force, pose, msg, size)) != STEWART_OK) return s;
    *out = o;
    msg[0] = '\0';
    return STEWART_OK;
}
