#include "core/joints/primitives.hpp"

namespace mbs {

namespace {
const Vec3 kZero = Vec3::Zero();
Eigen::Map<const Vec3> position(const double *q) { return Eigen::Map<const Vec3>(q); }
Vec3 velocity(const double *v) { return v ? Vec3(v[0], v[1], v[2]) : Vec3::Zero(); }
}  // namespace

void point_coincidence(const JointInput &in, const RowWriter &w, int row) {
    const Attached ui = attach(in.q_i, in.v_i, in.def.point_i);
    const Attached uj = attach(in.q_j, in.v_j, in.def.point_j);
    const Vec3 phi = position(in.q_i) + ui.world - position(in.q_j) - uj.world;
    const Vec3 gamma = -(ui.quad - uj.quad);
    for (int k = 0; k < 3; ++k) {
        w.phi(row + k, phi[k]);
        w.phi_t(row + k, 0.0);
        w.gamma(row + k, gamma[k]);
        if (w.want_jac()) {
            Vec3 e = Vec3::Zero();
            e[k] = 1.0;
            put(w.jac_i(row + k), e, ui.B.row(k));
            put(w.jac_j(row + k), -e, -uj.B.row(k));
        }
    }
}

void dot1(const JointInput &in, const RowWriter &w, int row, const Vec3 &a_local,
          const Vec3 &b_local) {
    const Attached a = attach(in.q_i, in.v_i, a_local);
    const Attached b = attach(in.q_j, in.v_j, b_local);
    w.phi(row, a.world.dot(b.world));
    w.phi_t(row, 0.0);
    w.gamma(row, -(a.quad.dot(b.world) + 2.0 * a.rate.dot(b.rate) + a.world.dot(b.quad)));
    if (w.want_jac()) {
        put(w.jac_i(row), kZero, b.world.transpose() * a.B);
        put(w.jac_j(row), kZero, a.world.transpose() * b.B);
    }
}

void dot2(const JointInput &in, const RowWriter &w, int row, const Vec3 &a_local,
          const DriverValue *target) {
    const Attached a = attach(in.q_i, in.v_i, a_local);
    const Attached ui = attach(in.q_i, in.v_i, in.def.point_i);
    const Attached uj = attach(in.q_j, in.v_j, in.def.point_j);
    const Vec3 d = position(in.q_j) + uj.world - position(in.q_i) - ui.world;
    const Vec3 d_rate = velocity(in.v_j) + uj.rate - velocity(in.v_i) - ui.rate;
    const Vec3 d_quad = uj.quad - ui.quad;
    double phi = a.world.dot(d), phi_t = 0.0;
    double gamma = -(a.quad.dot(d) + 2.0 * a.rate.dot(d_rate) + a.world.dot(d_quad));
    if (target) {
        phi -= target->value;
        phi_t = -target->rate;
        gamma += target->accel;  // -Phi_tt
    }
    w.phi(row, phi);
    w.phi_t(row, phi_t);
    w.gamma(row, gamma);
    if (w.want_jac()) {
        put(w.jac_i(row), -a.world, d.transpose() * a.B - a.world.transpose() * ui.B);
        put(w.jac_j(row), a.world, a.world.transpose() * uj.B);
    }
}

}  // namespace mbs
