// The classical washout (Reid & Nahon 1985) with tilt coordination: the vehicle's specific force
// and angular velocity to the platform's excursion from home, its rates and accelerations, in the
// solvers' z-up base frame (stewart/stewart_cueing.h has the equations).
#pragma once

#include "cueing/washout_filter.hpp"
#include "stewart/stewart_cueing.h"

namespace stewart {
namespace cueing {

// The filters and constants made once from the options.
struct ClassicalDesign {
    FilterDesign translation, tilt, rotation;
    double translation_gain[3];  // k_i
    double tilt_gain[2];         // k_x w_l^2, k_y w_l^2
    double rotation_gain[3];
    double gravity;  // g [m/s2], the rest value of the specific force's z
    double tilt_max, tilt_rate_max;
    double head[3];  // solvers' z-up platform frame
};

// The three discretised filters for the last dt (a cache, not state: a step of another dt
// makes it again).
struct ClassicalSteps {
    double dt = -1.0;
    FilterStep translation, tilt, rotation;
};

// What the classical washout carries from one sample to the next.
struct ClassicalState {
    double translation[3][kMaxOrder];
    double tilt[2][kMaxOrder];
    double rotation[3][kMaxOrder];
    double tilt_angle[2];  // roll, pitch of the tilt after its rate limit [rad]
};

// The excursion from home: pose components (x, y, z, roll, pitch, yaw) and their derivatives.
struct Excursion {
    double q[6], q_dot[6], q_ddot[6];
    bool tilt_limited;
};

// head_x, head_y, head_z are in the machine's platform frame: z_down (frame_convention 1) turns
// them into the solvers' z-up one.
ClassicalDesign classical_design(const stewart_cueing_options &options, double gravity,
                                 bool z_down);

// One sample: the state advanced by input.dt with the input held, then the excursion at the end
// of the step.
void classical_step(const ClassicalDesign &design, ClassicalSteps &steps, ClassicalState &state,
                    const stewart_cueing_input &input, Excursion &out);

}  // namespace cueing
}  // namespace stewart
