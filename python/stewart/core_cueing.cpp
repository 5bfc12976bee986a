// stewart._core's cueing (cueing.py): a vehicle's specific force and angular velocity through a
// cueing unit (stewart/stewart_cueing.h), sample by sample, into the platform's poses; and back
// (head_motion.py): the platform frame's motion at those poses, through the library's own frames.
#include "_core.hpp"

#include "kinematics/frames.hpp"

extern "C" {
#include "stewart/stewart_cueing.h"
}

namespace stewart_core {

namespace {

const OptionTable<stewart_cueing_options> kCueingOptions = {
    "cueing", stewart_cueing_options_default, stewart_cueing_option_find, stewart_cueing_option_set,
    stewart_cueing_options_check};

// Owns a cueing object for the length of one call.
struct CueingObject {
    CueingObject(const Model &model, const stewart_cueing_options &o) {
        char message[STEWART_MESSAGE_SIZE];
        unit = stewart_cueing_create(model.get(), &o, message, sizeof message);
        if (!unit) fail(message);
    }
    ~CueingObject() { stewart_cueing_free(unit); }
    CueingObject(const CueingObject &) = delete;
    CueingObject &operator=(const CueingObject &) = delete;
    stewart_cueing *unit = nullptr;
};

// Row r of the inputs through the unit: the first row with dt = 0 (at rest before it), each later
// one held over the time since the row before (t must not decrease). A refused row raises
// ValueError naming it.
void cueing_run(const Model &model, Column<const double> t, Rows<const double, 3> force,
                Rows<const double, 3> omega,
                const std::vector<std::pair<std::string, double>> &options, Rows<double, 6> pose,
                Rows<double, 6> rate, Rows<double, 6> accel, Column<double> scale,
                Column<int> limited, Column<int> cut, Column<int> tilt_limited,
                Column<int> leg_limits) {
    const size_t n = t.shape(0);
    if (force.shape(0) != n || omega.shape(0) != n)
        fail("specific_force and angular_velocity must have one row per time");
    if (pose.shape(0) != n || rate.shape(0) != n || accel.shape(0) != n || scale.shape(0) != n ||
        limited.shape(0) != n || cut.shape(0) != n || tilt_limited.shape(0) != n ||
        leg_limits.shape(0) != n)
        fail("output arrays must have one row per time");
    const stewart_cueing_options o = options_by_name(kCueingOptions, options);
    CueingObject object(model, o);
    size_t bad = n;
    {
        nb::gil_scoped_release release;
        for (size_t r = 0; r < n; ++r) {
            stewart_cueing_input in;
            in.dt = r ? t(r) - t(r - 1) : 0.0;
            for (int i = 0; i < 3; ++i) {
                in.specific_force[i] = force(r, i);
                in.angular_velocity[i] = omega(r, i);
            }
            stewart_cueing_output out;
            if (stewart_cueing_step(object.unit, &in, &out) != STEWART_OK) {
                bad = r;
                break;
            }
            for (int i = 0; i < 6; ++i) {
                pose(r, i) = out.pose.q[i];
                rate(r, i) = out.pose.q_dot[i];
                accel(r, i) = out.pose.q_ddot[i];
            }
            scale(r) = out.scale;
            limited(r) = out.limited;
            cut(r) = out.cut;
            tilt_limited(r) = out.tilt_limited;
            leg_limits(r) = out.leg_limits;
        }
    }
    if (bad < n)
        fail(("row " + std::to_string(bad) + ": " + stewart_cueing_message(object.unit) +
              (bad && t(bad) < t(bad - 1) ? " (t must not decrease)" : ""))
                 .c_str());
}

// The platform frame's motion in the solvers' z-up base frame at each of the caller's poses (the
// tool in the user frame, angles in the rotation order, z down with frame_convention 1) with
// their rates and accelerations: the transform every solver applies on entry
// (kinematics/frames.hpp), so that what is felt is computed on the pose the solvers move to.
// rotation (N, 9): R row by row, platform axes to base axes.
void platform_motion(const Model &model, Poses pose, Poses rate, Poses accel,
                     Rows<double, 3> position, Rows<double, 3> velocity,
                     Rows<double, 3> acceleration, Rows<double, 9> rotation, Rows<double, 3> omega,
                     Rows<double, 3> alpha) {
    const size_t n = pose.shape(0);
    if (rate.shape(0) != n || accel.shape(0) != n)
        fail("pose, pose_rate and pose_accel must have one row per time");
    if (position.shape(0) != n || velocity.shape(0) != n || acceleration.shape(0) != n ||
        rotation.shape(0) != n || omega.shape(0) != n || alpha.shape(0) != n)
        fail("output arrays must have one row per time");
    const stewart::Frames frames = stewart::frames_of(*stewart_model_params(model.get()));
    nb::gil_scoped_release release;
    for (size_t r = 0; r < n; ++r) {
        stewart_pose tool;
        for (int i = 0; i < 6; ++i) {
            tool.q[i] = pose(r, i);
            tool.q_dot[i] = rate(r, i);
            tool.q_ddot[i] = accel(r, i);
        }
        const stewart::Motion m = stewart::platform_motion_of_pose(frames, tool);
        for (int i = 0; i < 3; ++i) {
            position(r, i) = m.position[i];
            velocity(r, i) = m.velocity[i];
            acceleration(r, i) = m.acceleration[i];
            omega(r, i) = m.omega[i];
            alpha(r, i) = m.alpha[i];
            for (int j = 0; j < 3; ++j) rotation(r, 3 * i + j) = m.rotation(i, j);
        }
    }
}

}  // namespace

void bind_cueing(nb::module_ &m) {
    m.def("platform_motion", &platform_motion, nb::arg("model"), nb::arg("pose"), nb::arg("rate"),
          nb::arg("accel"), nb::arg("position"), nb::arg("velocity"), nb::arg("acceleration"),
          nb::arg("rotation"), nb::arg("omega"), nb::arg("alpha"));
    // The model's gravity [m/s2] in the z-up world (base) frame, whatever the frame convention.
    m.def("model_gravity", [](const Model &model) {
        const double *g = stewart_model_params(model.get())->gravity;
        return std::make_tuple(g[0], g[1], g[2]);
    });
    m.def("cueing_run", &cueing_run, nb::arg("model"), nb::arg("t"), nb::arg("specific_force"),
          nb::arg("angular_velocity"), nb::arg("options"), nb::arg("pose"), nb::arg("rate"),
          nb::arg("accel"), nb::arg("scale"), nb::arg("limited"), nb::arg("cut"),
          nb::arg("tilt_limited"), nb::arg("leg_limits"));
    m.attr("CUEING_ALGORITHMS") = STEWART_CUEING_ALGORITHMS;
}

}  // namespace stewart_core
