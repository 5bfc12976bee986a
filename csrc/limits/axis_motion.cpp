#include "limits/axis_motion.hpp"

#include <algorithm>
#include <cmath>

namespace stewart {

namespace {

// Past this (rad) below 2 pi a root's angle is a root at 0 rounded down: a pose within its
// stroke has its next crossing ahead of it, at t in [0, 2 pi).
constexpr double kFullTurnSlack = 1e-9;

// The angle x as a turn ahead of t = 0, in [0, 2 pi).
double ahead(double x) {
    double t = std::remainder(x, 2.0 * M_PI);
    if (t < 0.0) t += 2.0 * M_PI;
    return t > 2.0 * M_PI - kFullTurnSlack ? 0.0 : t;
}

// The first t >= 0 at which t^2 + 2 b t + c0 (c0 = L^2 - s^2) crosses zero leaving the
// stroke: upward through stroke_max (c0 <= 0), downward through stroke_min (c0 >= 0); HUGE_VAL
// if never. Each root in the form that does not cancel.
double translation_root(double b, double c0, bool upper) {
    const double discriminant = b * b - c0;
    if (discriminant < 0.0) return HUGE_VAL;
    const double s = std::sqrt(discriminant);
    if (upper) return std::max(0.0, b <= 0.0 ? s - b : -c0 / (b + s));
    return b < 0.0 ? std::max(0.0, c0 / (s - b)) : HUGE_VAL;
}

}  // namespace

AxisMotion axis_motion(const Frames &f, const double q[6], int axis, double sign) {
    AxisMotion m;
    m.rotation = axis >= 3;
    Eigen::Vector3d user;  // the direction in the user frame
    if (axis < 3) user = Eigen::Vector3d::Unit(axis);
    else user = angle_axis_in_order(f.rotation_order, q, axis);
    m.direction = sign * (f.user_rotation * user);
    m.centre = f.user_origin + f.user_rotation * Eigen::Vector3d(q[0], q[1], q[2]);
    return m;
}

void leg_state(const LimitConstants &c, const double platform[6], LegState &out) {
    const PlatformGeometry &g = c.geometry;
    out.rotation = rotation_from_rpy(platform[3], platform[4], platform[5]);
    out.kinematics.arm.noalias() = out.rotation * g.platform_points;
    const Eigen::Vector3d position(platform[0], platform[1], platform[2]);
    out.has_direction = true;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        out.top.col(k) = position + out.kinematics.arm.col(k);
        const Eigen::Vector3d d = out.top.col(k) - g.base_points.col(k);
        const double L = d.norm();
        const bool defined = L > g.min_length;
        out.has_direction = out.has_direction && defined;
        out.kinematics.axis.col(k) =
            defined ? Eigen::Vector3d(d / L) : Eigen::Vector3d(-c.base_neutral.col(k));
        out.kinematics.length[k] = L;
    }
}

Eigen::Vector3d point_velocity(const AxisMotion &m, const Eigen::Vector3d &x) {
    return m.rotation ? Eigen::Vector3d(m.direction.cross(x - m.centre)) : m.direction;
}

double point_speed(const AxisMotion &m, const Eigen::Vector3d &x) {
    return m.rotation ? m.direction.cross(x - m.centre).norm() : 1.0;
}

double first_stroke_end(const LimitConstants &c, const LegState &legs, const AxisMotion &m,
                        double extent, int &leg) {
    double first = extent;
    leg = 0;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Eigen::Vector3d base = c.geometry.base_points.col(k);
        const double smin2 = c.stroke_min[k] * c.stroke_min[k];
        const double smax2 = c.stroke_max[k] * c.stroke_max[k];
        double t = HUGE_VAL;
        if (!m.rotation) {
            const Eigen::Vector3d d = legs.top.col(k) - base;
            const double b = d.dot(m.direction), L2 = d.squaredNorm();
            t = std::min(translation_root(b, L2 - smax2, true),
                         translation_root(b, L2 - smin2, false));
        } else {
            // d(t) = p + r_perp cos t + (w x r_perp) sin t with r the joint's offset from the
            // axis' centre, r_perp its part normal to the axis, p the rest.
            const Eigen::Vector3d &w = m.direction;
            const Eigen::Vector3d r = legs.top.col(k) - m.centre;
            const Eigen::Vector3d r_perp = r - w * w.dot(r);
            const Eigen::Vector3d p = legs.top.col(k) - r_perp - base;
            const double A = p.squaredNorm() + r_perp.squaredNorm();
            const double B = 2.0 * p.dot(r_perp), C = 2.0 * p.dot(w.cross(r_perp));
            // L^2 = A + rho cos(t - phi): above s^2 for t - phi in (-delta, delta).
            const double rho = std::hypot(B, C), phi = std::atan2(C, B);
            if (rho > 0.0) {
                const double up = (smax2 - A) / rho, down = (smin2 - A) / rho;
                if (up >= -1.0 && up <= 1.0) t = std::min(t, ahead(phi - std::acos(up)));
                if (down >= -1.0 && down <= 1.0) t = std::min(t, ahead(phi + std::acos(down)));
            }
        }
        if (t < first) {
            first = t;
            leg = k + 1;
        }
    }
    return first;
}

}  // namespace stewart
