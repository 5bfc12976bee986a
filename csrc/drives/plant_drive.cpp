// The plant's regularised drive law (plant_drive.hpp).
#include "drives/plant_drive.hpp"

#include <cmath>

namespace stewart {

double smooth_sign(double v, double smoothing_speed) {
    return v / std::sqrt(v * v + smoothing_speed * smoothing_speed);
}

double drive_current(const LegDrive &d, double leg_force, double L_dot, double L_ddot,
                     double smoothing_speed) {
    const double nut = leg_force + friction_force(d, L_dot, smoothing_speed);
    const double x = (nut >= 0 ? 1.0 : -1.0) * smooth_sign(L_dot, smoothing_speed);
    const double ideal = nut / screw_force_factor(d, x);  // sign(F_i) = sign(F_nut): e > 0
    return (ideal + reflected_mass(d) * L_ddot) / (d.motor_per_leg * d.torque_constant);
}

}  // namespace stewart
