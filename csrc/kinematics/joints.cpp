#include "kinematics/joints.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "util/message.hpp"
#include "util/range.hpp"

namespace stewart {

namespace {

using Vec3 = Eigen::Vector3d;

// A Cardan axis given as neither zero nor unit to this tolerance is refused: a datasheet's
// rounded unit vector passes, a typo does not.
constexpr double kUnitTolerance = 1e-6;
// A Cardan arm closer to its leg than this (sine of the angle) at home is locked there.
constexpr double kMinArmSine = 1e-3;
// Two joints of one side closer than this (relative to the side's size) are one point.
constexpr double kCoincident = 1e-9;

bool coincide(const Matrix36 &points, int i, int j, double side_size) {
    return (points.col(i) - points.col(j)).norm() <= kCoincident * side_size;
}

bool is_joints(const stewart_params &p) { return p.geometry == 1.0; }

Vec3 triple(const double *values, int k) {
    return Vec3(values[3 * k], values[3 * k + 1], values[3 * k + 2]);
}

// One side's joints and arms. Geometry 0: on the circle, the tangent from the angle (as the
// thesis); geometry 1: as given, the tangent from the joint's azimuth.
void fill_side(bool joints, double radius, const double *angle, const double *point,
               const double *axis, Matrix36 &points, Matrix36 &arms, double &size) {
    size = joints ? 0.0 : radius;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        if (joints) {
            points.col(k) = triple(point, k);
            size = std::max(size, points.col(k).norm());
        } else {
            points.col(k) << radius * std::cos(angle[k]), radius * std::sin(angle[k]), 0.0;
        }
        const Vec3 given = triple(axis, k);
        const double norm = given.norm();
        if (norm > 0) {
            arms.col(k) = given / norm;
        } else if (joints) {
            const double x = points(0, k), y = points(1, k), r = std::hypot(x, y);
            arms.col(k) << -y / r, x / r, 0.0;
        } else {
            arms.col(k) << -std::sin(angle[k]), std::cos(angle[k]), 0.0;
        }
    }
}

// "base_joint[4..6]" or "base_angle[2]": the field(s) that place joint k of a side.
std::string joint_field(bool joints, const char *side, int k) {
    char text[48];
    if (joints) std::snprintf(text, sizeof text, "%s_joint[%d..%d]", side, 3 * k + 1, 3 * k + 3);
    else std::snprintf(text, sizeof text, "%s_angle[%d]", side, k + 1);
    return text;
}

std::string vector_text(const Vec3 &v) {
    return std::string("(") + ExactText(v[0]).c_str() + ", " + ExactText(v[1]).c_str() + ", " +
           ExactText(v[2]).c_str() + ")";
}

// The checks of one side (base: the arms are fixed in the world; platform: in the platform
// frame, which is the world's at home).
stewart_status check_side(const stewart_params &p, const JointGeometry &g, bool base, char *msg,
                          size_t size) {
    const bool joints = is_joints(p);
    const char *side = base ? "base" : "platform";
    const Matrix36 &points = base ? g.base_points : g.platform_points;
    const double *axis = base ? p.base_cardan_axis : p.platform_cardan_axis;
    const double side_size = base ? g.base_size : g.platform_size;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Vec3 given = triple(axis, k);
        const double norm = given.norm();
        char field[40];
        std::snprintf(field, sizeof field, "%s_cardan_axis[%d..%d]", side, 3 * k + 1, 3 * k + 3);
        if (norm > 0 && std::fabs(norm - 1.0) > kUnitTolerance)
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "%s = %s has length %s: a Cardan axis must be a unit vector (or "
                               "zero for the tangent at the joint's azimuth)",
                               field, vector_text(given).c_str(), ExactText(norm).c_str());
        if (norm == 0 && joints &&
            std::hypot(points(0, k), points(1, k)) <= kCoincident * side_size)
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "%s = %s m is on the z axis, so its azimuth and the default Cardan "
                               "axis are not defined: give %s",
                               joint_field(joints, side, k).c_str(),
                               vector_text(points.col(k)).c_str(), field);
        const Vec3 leg =
            Vec3(0, 0, p.home_height) + g.platform_points.col(k) - g.base_points.col(k);
        const double length = leg.norm();
        if (!(length > kCoincident * (g.base_size + g.platform_size + std::fabs(p.home_height))))
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "leg %d has length %s m at home (z = home_height = %s m): %s and "
                               "%s must differ there",
                               k + 1, ExactText(length).c_str(), ExactText(p.home_height).c_str(),
                               joint_field(joints, "base", k).c_str(),
                               joint_field(joints, "platform", k).c_str());
        const Vec3 arm = (base ? g.base_arms : g.platform_arms).col(k);
        const double sine = arm.cross(leg / length).norm();
        if (!(sine >= kMinArmSine))
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "%s = %s lies along leg %d at home (sine of the angle %s): the "
                               "Cardan is locked there; its fixed arm must cross the leg",
                               field, vector_text(norm > 0 ? given : Vec3(arm)).c_str(), k + 1,
                               ExactText(sine).c_str());
    }
    return STEWART_OK;
}

}  // namespace

JointGeometry joint_geometry(const stewart_params &p) {
    JointGeometry g;
    const bool joints = is_joints(p);
    fill_side(joints, p.base_radius, p.base_angle, p.base_joint, p.base_cardan_axis, g.base_points,
              g.base_arms, g.base_size);
    fill_side(joints, p.platform_radius, p.platform_angle, p.platform_joint, p.platform_cardan_axis,
              g.platform_points, g.platform_arms, g.platform_size);
    return g;
}

stewart_status check_joint_geometry(const stewart_params &p, char *msg, size_t size) {
    if (p.geometry != 0.0 && p.geometry != 1.0)
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "geometry = %s must be 0 (joints on the circles of base_radius, "
                           "base_angle, platform_radius, platform_angle) or 1 (base_joint and "
                           "platform_joint as given)",
                           ExactText(p.geometry).c_str());
    const JointGeometry g = joint_geometry(p);
    // Two legs may share a joint on one side (genhexkins' default base, 6-3 platforms), not on
    // both: the same leg twice leaves the platform free (the leg Jacobian is singular everywhere).
    const bool joints = is_joints(p);
    for (int k = 0; k < STEWART_LEGS; ++k)
        for (int j = 0; j < k; ++j)
            if (coincide(g.base_points, j, k, g.base_size) &&
                coincide(g.platform_points, j, k, g.platform_size))
                return set_message(msg, size, STEWART_ERR_PARAMETER,
                                   "legs %d and %d are one leg: %s and %s at %s m, %s and %s at "
                                   "%s m; the platform is then free at every pose",
                                   j + 1, k + 1, joint_field(joints, "base", j).c_str(),
                                   joint_field(joints, "base", k).c_str(),
                                   vector_text(g.base_points.col(k)).c_str(),
                                   joint_field(joints, "platform", j).c_str(),
                                   joint_field(joints, "platform", k).c_str(),
                                   vector_text(g.platform_points.col(k)).c_str());
    stewart_status s = check_side(p, g, true, msg, size);
    if (s == STEWART_OK) s = check_side(p, g, false, msg, size);
    return s;
}

}  // namespace stewart
