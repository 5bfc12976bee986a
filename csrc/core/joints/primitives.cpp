#include "core/joints/primitives.hpp"

#include "core/euler_pairs.hpp"

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
// attach_i(in, out, ui) into a and attach_j(in, out, uj) into b, body i's products and body j's
// in the two lanes.
void attach_both(const JointInput &in, const JointOutput &out, const Vec3 &ui, const Vec3 &uj,
                 Attached &a, Attached &b) {
    times_two(in.frame_i->A, ui, in.frame_j->A, uj, a.world, b.world);
    const bool rates_i = out.gamma && in.v_i, rates_j = out.gamma && in.v_j;
    if (rates_i && rates_j) {
        times_two(in.frame_i->rate, ui, in.frame_j->rate, uj, a.rate, b.rate);
        times_two(in.frame_i->quad, ui, in.frame_j->quad, uj, a.quad, b.quad);
        return;
    }
    if (rates_i) a.rate = times(in.frame_i->rate, ui), a.quad = times(in.frame_i->quad, ui);
    if (rates_j) b.rate = times(in.frame_j->rate, uj), b.quad = times(in.frame_j->quad, uj);
}

// dot1's row without the rates (no gamma), from a = A_i a_local and b = A_j b_local already
// formed (rows that share them form them once).
[[gnu::always_inline]] inline void dot1_formed(const JointInput &in, const RowWriter &w, int row,
                                               const Vec3 &a_local, const Vec3 &b_local,
                                               const Vec3 &a, const Vec3 &b) {
    w.phi(row, a.dot(b));
    w.phi_t(row, 0.0);
    if (w.want_jac()) {
        double *ri = w.jac_i(row), *rj = w.jac_j(row);
        ri[0] = ri[1] = ri[2] = 0.0, rj[0] = rj[1] = rj[2] = 0.0;
        rotation_row_two(in.q_i + 3, a_local, b, ri + 3, in.q_j + 3, b_local, a, rj + 3);
    }
}

// dot2's value, phi_t and Jacobian rows (not gamma), from a = A_i a_local already formed and,
// for the Jacobian, lever = rotation_row(p_i, point_i, a) (rows that share a body pair their
// levers).
[[gnu::always_inline]] inline void dot2_formed(const JointInput &in, const RowWriter &w, int row,
                                               const Vec3 &a_local, const Vec3 &a,
                                               const double *lever, const Separation &sep,
                                               const DriverValue *target = nullptr) {
    w.phi(row, a.dot(sep.d) - (target ? target->value : 0.0));
    w.phi_t(row, target ? -target->rate : 0.0);
    if (w.want_jac()) {
        double *ri = w.jac_i(row), *rj = w.jac_j(row);
        double turn[4];  // v^T B row of a turning with body i
        rotation_row_two(in.q_i + 3, a_local, sep.d, turn, in.q_j + 3, in.def.point_j, a, rj + 3);
        for (int c = 0; c < 3; ++c) ri[c] = -a[c], rj[c] = a[c];
        for (int c = 0; c < 4; ++c) ri[3 + c] = turn[c] - lever[c];
    }
}

[[gnu::always_inline]] inline void point_coincidence_rows(const JointInput &in, const RowWriter &w,
                                                          int row) {
    Attached ui, uj;
    attach_both(in, w.out, in.def.point_i, in.def.point_j, ui, uj);
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
        Mat34 Bi, Bj;
        rotate_jacobian_two(in.q_i + 3, in.def.point_i, in.q_j + 3, in.def.point_j, Bi, Bj);
        for (int k = 0; k < 3; ++k) {
            double *ri = w.jac_i(row + k), *rj = w.jac_j(row + k);
            for (int c = 0; c < 3; ++c) ri[c] = (c == k) ? 1.0 : 0.0, rj[c] = (c == k) ? -1.0 : 0.0;
            for (int c = 0; c < 4; ++c) ri[3 + c] = Bi(k, c), rj[3 + c] = -Bj(k, c);
        }
    }
}

[[gnu::always_inline]] inline void dot1_rows(const JointInput &in, const RowWriter &w, int row,
                                             const Vec3 &a_local, const Vec3 &b_local) {
    if (!w.out.gamma) {  // Newton's pass: the same products, without the rates' bookkeeping
        Vec3 a, b;
        times_two(in.frame_i->A, a_local, in.frame_j->A, b_local, a, b);
        dot1_formed(in, w, row, a_local, b_local, a, b);
        return;
    }
    Attached a, b;
    attach_both(in, w.out, a_local, b_local, a, b);
    w.phi(row, a.world.dot(b.world));
    w.phi_t(row, 0.0);
    if (w.out.gamma)
        w.gamma(row, -(a.quad.dot(b.world) + 2.0 * a.rate.dot(b.rate) + a.world.dot(b.quad)));
    if (w.want_jac()) {
        double *ri = w.jac_i(row), *rj = w.jac_j(row);
        ri[0] = ri[1] = ri[2] = 0.0, rj[0] = rj[1] = rj[2] = 0.0;
        rotation_row_two(in.q_i + 3, a_local, b.world, ri + 3, in.q_j + 3, b_local, a.world,
                         rj + 3);
    }
}

}  // namespace

void point_coincidence(const JointInput &in, const RowWriter &w, int row) {
    point_coincidence_rows(in, w, row);
}

void dot1(const JointInput &in, const RowWriter &w, int row, const Vec3 &a_local,
          const Vec3 &b_local) {
    dot1_rows(in, w, row, a_local, b_local);
}

void cardan_rows(const JointInput &in, const JointOutput &out) {
    const RowWriter w{out};
    point_coincidence_rows(in, w, 0);
    dot1_rows(in, w, 3, in.def.axis_i[0], in.def.axis_j[0]);
}

Separation separation(const JointInput &in, const JointOutput &out) {
    const double *vi = rate_source(in, true, out), *vj = rate_source(in, false, out);
    Attached ui, uj;
    attach_both(in, out, in.def.point_i, in.def.point_j, ui, uj);
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
    double lever[4];  // v^T B row of body i's point's lever
    if (w.want_jac()) rotation_row(in.q_i + 3, in.def.point_i, a.world, lever);
    dot2_formed(in, w, row, a_local, a.world, lever, sep, target);
    if (w.out.gamma) {
        double gamma = -(a.quad.dot(sep.d) + 2.0 * a.rate.dot(sep.rate) + a.world.dot(sep.quad));
        if (target) gamma += target->accel;  // -Phi_tt
        w.gamma(row, gamma);
    }
}

void evaluate_cylindrical_with_distance(const JointInput &in, const JointOutput &out,
                                        const JointInput &driver, const JointOutput &driver_out) {
    const RowWriter w{out}, wd{driver_out};
    if (out.gamma || driver_out.gamma) {  // the rates' pass: the two calls as they are
        cylindrical_rows(in, out, w);
        dot2(driver, wd, 0, driver.def.axis_i[2], separation(driver, driver_out), driver.drive);
        return;
    }
    // Newton's pass: A_i v1, A_i v2, the driver's A_i axis, A_j v_j and the separation formed
    // once each (the separate calls formed A_i v1, A_i v2 and the separation twice).
    Vec3 a1, a2, axis, vj;
    times_two(in.frame_i->A, in.def.axis_i[0], in.frame_i->A, in.def.axis_i[1], a1, a2);
    times_two(in.frame_i->A, driver.def.axis_i[2], in.frame_j->A, in.def.axis_j[2], axis, vj);
    const Separation d = separation(in, out);
    dot1_formed(in, w, 0, in.def.axis_i[0], in.def.axis_j[2], a1, vj);
    dot1_formed(in, w, 1, in.def.axis_i[1], in.def.axis_j[2], a2, vj);
    double lever1[4], lever2[4], lever[4];  // the dot-2 rows' levers, two of them paired
    if (w.want_jac() || wd.want_jac()) {
        rotation_row_two(in.q_i + 3, in.def.point_i, a1, lever1, in.q_i + 3, in.def.point_i, a2,
                         lever2);
        rotation_row(in.q_i + 3, driver.def.point_i, axis, lever);
    }
    dot2_formed(in, w, 2, in.def.axis_i[0], a1, lever1, d);
    dot2_formed(in, w, 3, in.def.axis_i[1], a2, lever2, d);
    dot2_formed(driver, wd, 0, driver.def.axis_i[2], axis, lever, d, driver.drive);
}

}  // namespace mbs
