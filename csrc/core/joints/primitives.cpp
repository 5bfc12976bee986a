#include "core/joints/primitives.hpp"

namespace mbs {

namespace {
Eigen::Map<const Vec3> position(const double *q) { return Eigen::Map<const Vec3>(q); }
Vec3 velocity(const double *v) { return v ? Vec3(v[0], v[1], v[2]) : Vec3::Zero(); }
const double *rate_source(const JointInput &in, bool body_i, const JointOutput &out) {
    return out.gamma ? (body_i ? in.v_i : in.v_j) : nullptr;
}
Attached attach_i(const JointInput &in, const JointOutput &out, const Vec3 &u) {
    return attach(*in.frame_i, out.gamma && in.v_i, u);
}
Attached attach_j(const JointInput &in, const JointOutput &out, const Vec3 &u) {
    return attach(*in.frame_j, out.gamma && in.v_j, u);
}
}  // namespace

void point_coincidence(const JointInput &in, const RowWriter &w, int row) {
    const Attached ui = attach_i(in, w.out, in.def.point_i);
    const Attached uj = attach_j(in, w.out, in.def.point_j);
    if (w.out.phi) {
        const Vec3 phi = position(in.q_i) + ui.world - position(in.q_j) - uj.world;
        for (int k = 0; k < 3; ++k) w.phi(row + k, phi[k]);
    }
    if (w.out.gamma) {
        const Vec3 gamma = uj.quad - ui.quad;
        for (int k = 0; k < 3; ++k) w.gamma(row + k, gamma[k]);
    }
    for (int k = 0; k < 3; ++k) w.phi_t(row + k, 0.0);
    if (w.want_jac()) {
        const Mat34 Bi = rotate_jacobian(in.q_i + 3, in.def.point_i);
        const Mat34 Bj = rotate_jacobian(in.q_j + 3, in.def.point_j);
        for (int k = 0; k < 3; ++k) {
            double *ri = w.jac_i(row + k), *rj = w.jac_j(row + k);
            for (int c = 0; c < 3; ++c) ri[c] = (c == k) ? 1.0 : 0.0, rj[c] = (c == k) ? -1.0 : 0.0;
            for (int c = 0; c < 4; ++c) ri[3 + c] = Bi(k, c), rj[3 + c] = -Bj(k, c);
        }
    }
}

void dot1(const JointInput &in, const RowWriter &w, int row, const Vec3 &a_local,
          const Vec3 &b_local) {
    if (!w.out.gamma) {  // Newton's pass: the same products, without the rates' bookkeeping
        const Vec3 a = times(in.frame_i->A, a_local), b = times(in.frame_j->A, b_local);
        w.phi(row, a.dot(b));
        w.phi_t(row, 0.0);
        if (w.want_jac()) {
            double *ri = w.jac_i(row), *rj = w.jac_j(row);
            ri[0] = ri[1] = ri[2] = 0.0, rj[0] = rj[1] = rj[2] = 0.0;
            rotation_row(in.q_i + 3, a_local, b, ri + 3);
            rotation_row(in.q_j + 3, b_local, a, rj + 3);
        }
        return;
    }
    const Attached a = attach_i(in, w.out, a_local);
    const Attached b = attach_j(in, w.out, b_local);
    w.phi(row, a.world.dot(b.world));
    w.phi_t(row, 0.0);
    if (w.out.gamma)
        w.gamma(row, -(a.quad.dot(b.world) + 2.0 * a.rate.dot(b.rate) + a.world.dot(b.quad)));
    if (w.want_jac()) {
        const Vec3 zero = Vec3::Zero();
        put(w.jac_i(row), zero, row_of_rotate_jacobian(in.q_i + 3, a_local, b.world));
        put(w.jac_j(row), zero, row_of_rotate_jacobian(in.q_j + 3, b_local, a.world));
    }
}

Separation separation(const JointInput &in, const JointOutput &out) {
    const double *vi = rate_source(in, true, out), *vj = rate_source(in, false, out);
    const Attached ui = attach_i(in, out, in.def.point_i);
    const Attached uj = attach_j(in, out, in.def.point_j);
    Separation s;
    s.d = position(in.q_j) + uj.world - position(in.q_i) - ui.world;
    if (out.gamma) {
        s.rate = velocity(vj) + uj.rate - velocity(vi) - ui.rate;
        s.quad = uj.quad - ui.quad;
    }
    return s;
}

void dot2(const JointInput &in, const RowWriter &w, int row, const Vec3 &a_local,
          const Separation &sep, const DriverValue *target) {
    const Attached a = attach_i(in, w.out, a_local);
    w.phi(row, a.world.dot(sep.d) - (target ? target->value : 0.0));
    w.phi_t(row, target ? -target->rate : 0.0);
    if (w.out.gamma) {
        double gamma = -(a.quad.dot(sep.d) + 2.0 * a.rate.dot(sep.rate) + a.world.dot(sep.quad));
        if (target) gamma += target->accel;  // -Phi_tt
        w.gamma(row, gamma);
    }
    if (w.want_jac()) {
        put(w.jac_i(row), -a.world,
            row_of_rotate_jacobian(in.q_i + 3, a_local, sep.d) -
                row_of_rotate_jacobian(in.q_i + 3, in.def.point_i, a.world));
        put(w.jac_j(row), a.world, row_of_rotate_jacobian(in.q_j + 3, in.def.point_j, a.world));
    }
}

}  // namespace mbs
