#include "core/builder.hpp"

#include <cmath>

#include "core/message.hpp"

using mbs::set_message;

namespace mbs {

namespace {

bool finite(const Vec3 &v) { return v.allFinite(); }

// (v1, v2) with (v1, v2, v) right-handed and orthonormal.
void perpendiculars(const Vec3 &v, Vec3 &v1, Vec3 &v2) {
    Vec3 e = Vec3::Zero();
    int k = 0;
    for (int i = 1; i < 3; ++i)
        if (std::fabs(v[i]) < std::fabs(v[k])) k = i;
    e[k] = 1.0;
    v1 = v.cross(e).normalized();
    v2 = v.cross(v1);
}

// A joint of `type` between body bi (point u_i) and body bj (point u_j), axes to be filled.
JointDef two_body(JointType type, int bi, const Vec3 &ui, int bj, const Vec3 &uj) {
    JointDef j;
    j.type = type;
    j.body_i = bi, j.body_j = bj, j.point_i = ui, j.point_j = uj;
    return j;
}

}  // namespace

int Builder::check_open() {
    if (m.finalized)
        return set_message(msg, size, MBS_ERR_ARGUMENT,
                           "the model is finalised: no more bodies or joints can be added");
    return MBS_OK;
}

int Builder::check_body(int b, const char *what) {
    if (b < 0 || b >= static_cast<int>(m.bodies.size()))
        return set_message(msg, size, MBS_ERR_ARGUMENT,
                           "%s = %d is not a body index (the model has %zu bodies)", what, b,
                           m.bodies.size());
    return MBS_OK;
}

int Builder::check_pair(int bi, int bj) {
    int s;
    if ((s = check_open()) || (s = check_body(bi, "body_i")) || (s = check_body(bj, "body_j")))
        return s;
    if (bi == bj)
        return set_message(msg, size, MBS_ERR_ARGUMENT,
                           "body_i = body_j = %d: a joint needs two different bodies", bi);
    return MBS_OK;
}

int Builder::check_free(int b) {
    if (m.bodies[b].fixed || m.bodies[b].pose_driven)
        return set_message(msg, size, MBS_ERR_ARGUMENT, "body %d is already fixed or pose-driven",
                           b);
    return MBS_OK;
}

int Builder::check_direction(const Vec3 &v, const char *what, Vec3 &unit) {
    if (!finite(v) || !(v.norm() > 1e-12))
        return set_message(msg, size, MBS_ERR_ARGUMENT,
                           "%s = (%g, %g, %g) must be a finite nonzero direction", what, v[0], v[1],
                           v[2]);
    unit = v.normalized();
    return MBS_OK;
}

int Builder::add(JointDef j) {
    if (!finite(j.point_i) || !finite(j.point_j))
        return set_message(msg, size, MBS_ERR_ARGUMENT,
                           "attachment point (%g, %g, %g) / (%g, %g, %g) must be finite",
                           j.point_i[0], j.point_i[1], j.point_i[2], j.point_j[0], j.point_j[1],
                           j.point_j[2]);
    m.joints.push_back(j);
    return static_cast<int>(m.joints.size()) - 1;
}

int Builder::add_driver(JointDef j, int *slot) {
    int first = 0;
    for (const JointDef &k : m.joints) first += joint_type(k.type).drivers;
    j.driver = first;
    if (slot) *slot = first;
    return add(j);
}

Vec3 Builder::reference_image(int bi, int bj, const Vec3 &v) const {
    return rotation(m.bodies[bj].q_reference + 3).transpose() *
           rotate(m.bodies[bi].q_reference + 3, v);
}

int Builder::body(const char *name, double mass, const Vec3 &I, const double q[7]) {
    int s;
    if ((s = check_open())) return s;
    if (!(std::isfinite(mass) && mass >= 0))
        return set_message(msg, size, MBS_ERR_PARAMETER, "mass of body %s = %g must be >= 0",
                           name ? name : "?", mass);
    if (!finite(I) || I.minCoeff() < 0 || I[0] + I[1] < I[2] || I[1] + I[2] < I[0] ||
        I[0] + I[2] < I[1])
        return set_message(msg, size, MBS_ERR_PARAMETER,
                           "inertia of body %s = (%g, %g, %g) must be >= 0 and satisfy the "
                           "triangle inequalities",
                           name ? name : "?", I[0], I[1], I[2]);
    double pn = 0;
    for (int c = 0; c < 7; ++c)
        if (!std::isfinite(q[c]))
            return set_message(msg, size, MBS_ERR_ARGUMENT,
                               "q_reference[%d] of body %s is %g: it must be finite", c,
                               name ? name : "?", q[c]);
    for (int c = 3; c < 7; ++c) pn += q[c] * q[c];
    if (std::fabs(pn - 1.0) > 1e-9)
        return set_message(msg, size, MBS_ERR_ARGUMENT,
                           "Euler parameters of body %s have norm^2 %g: they must be unit",
                           name ? name : "?", pn);
    Body b;
    b.name = name ? name : "";
    b.mass = mass;
    b.inertia = I;
    for (int c = 0; c < 7; ++c) b.q_reference[c] = q[c];
    m.bodies.push_back(b);
    return static_cast<int>(m.bodies.size()) - 1;
}

int Builder::fix(int b) {
    int s;
    if ((s = check_open()) || (s = check_body(b, "body")) || (s = check_free(b))) return s;
    m.bodies[b].fixed = true;
    JointDef j;
    j.type = JointType::FixedBody;
    j.body_i = b;
    for (int c = 0; c < 7; ++c) j.q_fixed[c] = m.bodies[b].q_reference[c];
    return add(j);
}

int Builder::spherical(int bi, const Vec3 &ui, int bj, const Vec3 &uj) {
    int s;
    if ((s = check_pair(bi, bj))) return s;
    return add(two_body(JointType::Spherical, bi, ui, bj, uj));
}

int Builder::cardan(int bi, const Vec3 &ui, const Vec3 &si, int bj, const Vec3 &uj,
                    const Vec3 &sj) {
    int s;
    JointDef j = two_body(JointType::Cardan, bi, ui, bj, uj);
    if ((s = check_pair(bi, bj)) || (s = check_direction(si, "s_i", j.axis_i[0])) ||
        (s = check_direction(sj, "s_j", j.axis_j[0])))
        return s;
    return add(j);
}

int Builder::cylindrical(int bi, const Vec3 &ui, const Vec3 &vi, int bj, const Vec3 &uj,
                         const Vec3 &vj) {
    int s;
    JointDef j = two_body(JointType::Cylindrical, bi, ui, bj, uj);
    if ((s = check_pair(bi, bj)) || (s = check_direction(vi, "v_i", j.axis_i[2])) ||
        (s = check_direction(vj, "v_j", j.axis_j[2])))
        return s;
    perpendiculars(j.axis_i[2], j.axis_i[0], j.axis_i[1]);
    return add(j);
}

int Builder::revolute(int bi, const Vec3 &ui, const Vec3 &vi, int bj, const Vec3 &uj,
                      const Vec3 &vj) {
    const int k = cylindrical(bi, ui, vi, bj, uj, vj);
    if (k < 0) return k;
    JointDef &j = m.joints[k];
    j.type = JointType::Revolute;
    j.axis_j[0] = reference_image(bi, bj, j.axis_i[0]);  // zero angle of an angle driver
    return k;
}

int Builder::prismatic(int bi, const Vec3 &ui, const Vec3 &vi, int bj, const Vec3 &uj,
                       const Vec3 &vj) {
    const int k = cylindrical(bi, ui, vi, bj, uj, vj);
    if (k < 0) return k;
    JointDef &j = m.joints[k];
    j.type = JointType::Prismatic;
    j.axis_j[1] = reference_image(bi, bj, j.axis_i[1]);
    return k;
}

int Builder::weld(int bi, const Vec3 &ui, int bj, const Vec3 &uj) {
    int s;
    if ((s = check_pair(bi, bj))) return s;
    JointDef j = two_body(JointType::Weld, bi, ui, bj, uj);
    for (int c = 0; c < 3; ++c) {
        j.axis_i[c] = Vec3::Unit(c);
        j.axis_j[c] = reference_image(bi, bj, j.axis_i[c]);
    }
    return add(j);
}

int Builder::coordinate_driver(int b, int coordinate, int *slot) {
    int s;
    if ((s = check_open()) || (s = check_body(b, "body"))) return s;
    if (coordinate < 0 || coordinate > 6)
        return set_message(msg, size, MBS_ERR_ARGUMENT,
                           "coordinate = %d must be 0..6 (x, y, z, e0, e1, e2, e3)", coordinate);
    JointDef j;
    j.type = JointType::CoordinateDriver;
    j.body_i = b;
    j.coordinate = coordinate;
    return add_driver(j, slot);
}

int Builder::pose_driver(int b, int *slot) {
    int s;
    if ((s = check_open()) || (s = check_body(b, "body")) || (s = check_free(b))) return s;
    m.bodies[b].pose_driven = true;
    JointDef j;
    j.type = JointType::PoseDriver;
    j.body_i = b;
    return add_driver(j, slot);
}

int Builder::distance_driver(int joint, int *slot) {
    int s;
    if ((s = check_open())) return s;
    if (joint < 0 || joint >= static_cast<int>(m.joints.size()) ||
        (m.joints[joint].type != JointType::Cylindrical &&
         m.joints[joint].type != JointType::Prismatic))
        return set_message(msg, size, MBS_ERR_ARGUMENT,
                           "joint = %d is not a cylindrical or prismatic joint", joint);
    JointDef j = m.joints[joint];
    j.type = JointType::DistanceDriver;
    return add_driver(j, slot);
}

int Builder::angle_driver(int joint, int *slot) {
    int s;
    if ((s = check_open())) return s;
    if (joint < 0 || joint >= static_cast<int>(m.joints.size()) ||
        m.joints[joint].type != JointType::Revolute)
        return set_message(msg, size, MBS_ERR_ARGUMENT, "joint = %d is not a revolute joint",
                           joint);
    JointDef j = m.joints[joint];
    j.type = JointType::AngleDriver;
    return add_driver(j, slot);
}

}  // namespace mbs
