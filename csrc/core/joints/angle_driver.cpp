// Angle driver (1 equation) on a revolute joint: body j's arm x_j = axis_j[0] turns by f(t)
// about the axis, measured from x_i = axis_i[0] toward y_i = axis_i[1]. With c = x_i.x_j and
// s = y_i.x_j (cos and sin of the angle theta), Phi = sin f c - cos f s = sin(f - theta): well
// conditioned at every angle. Its multiplier is the torque driving body j about the axis.
#include "core/joints/primitives.hpp"

#include <cmath>

namespace mbs {

static void evaluate_angle_driver(const JointInput &in, const JointOutput &out) {
    const bool rows_needed = out.jac_i || out.gamma;  // gamma needs c_dot, s_dot
    double phi[2], gamma[2], jac_i[14], jac_j[14];
    const JointOutput parts{phi, rows_needed ? jac_i : nullptr, rows_needed ? jac_j : nullptr,
                            nullptr, out.gamma ? gamma : nullptr};
    dot1(in, RowWriter{parts}, 0, in.def.axis_i[0], in.def.axis_j[0]);
    dot1(in, RowWriter{parts}, 1, in.def.axis_i[1], in.def.axis_j[0]);
    const DriverValue &f = in.drive[0];
    const double sf = std::sin(f.value), cf = std::cos(f.value);
    const double c = phi[0], s = phi[1];
    if (out.phi) out.phi[0] = sf * c - cf * s;
    if (out.phi_t) out.phi_t[0] = f.rate * (cf * c + sf * s);
    if (out.jac_i)
        for (int k = 0; k < 7; ++k) {
            out.jac_i[k] = sf * jac_i[k] - cf * jac_i[7 + k];
            out.jac_j[k] = sf * jac_j[k] - cf * jac_j[7 + k];
        }
    if (out.gamma) {
        double c_dot = 0, s_dot = 0;
        for (int k = 0; k < 7; ++k) {
            c_dot += jac_i[k] * in.v_i[k] + jac_j[k] * in.v_j[k];
            s_dot += jac_i[7 + k] * in.v_i[k] + jac_j[7 + k] * in.v_j[k];
        }
        out.gamma[0] = sf * gamma[0] - cf * gamma[1] - 2.0 * f.rate * (cf * c_dot + sf * s_dot) -
                       f.accel * (cf * c + sf * s) + f.rate * f.rate * (sf * c - cf * s);
    }
}

extern const JointTypeInfo kAngleDriver = {"angle driver", 1, 1, 2, evaluate_angle_driver};

}  // namespace mbs
