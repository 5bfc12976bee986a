#include "limits/limit_check.hpp"

#include <algorithm>
#include <cmath>

#include "kinematics/motion.hpp"

namespace stewart {

namespace {

// One stroke end per leg.
double stroke_min_of(const stewart_params &p, int leg) { return p.stroke_min[leg]; }
double stroke_max_of(const stewart_params &p, int leg) { return p.stroke_max[leg]; }

// Column k of an x1, y1, z1, ..., z6 array, made unit; the fallback if it is zero.
Eigen::Vector3d unit_or(const double *xyz, int k, const Eigen::Vector3d &fallback) {
    const Eigen::Vector3d v(xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]);
    const double n = v.norm();
    return n > 0.0 ? Eigen::Vector3d(v / n) : fallback;
}

// The angle between two unit vectors, accurate near 0 and pi (acos is not).
double angle_between(const Eigen::Vector3d &u, const Eigen::Vector3d &v) {
    return std::atan2(u.cross(v).norm(), u.dot(v));
}

// The 15 pairs of legs, neighbours (which share a corner of the hexagon) first.
struct LegPair {
    int first, second;
};
constexpr LegPair kPairs[] = {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}, {0, 5}, {0, 2}, {1, 3},
                              {2, 4}, {3, 5}, {0, 4}, {1, 5}, {0, 3}, {1, 4}, {2, 5}};

// Keeps the smallest margin of a class and where it is.
void keep_smallest(stewart_limits_output &out, int index, double margin, int leg, int other) {
    if (margin < out.margin[index]) {
        out.margin[index] = margin;
        out.leg[index] = leg;
        out.other_leg[index] = other;
    }
}

// The joint-angle class's margin from the cosines of the legs' angles to their neutral axes
// (unit vectors: the angle grows as the cosine falls). With one limit for all legs only the
// largest angle needs its arc; the rotation turns platform-frame axes into the world.
void joint_margins(const double limit[STEWART_LEGS], bool uniform, const Matrix36 &axis,
                   const Matrix36 &neutral, const Eigen::Matrix3d *rotation,
                   const double cosine[STEWART_LEGS], stewart_limits_output &out, int index) {
    auto margin = [&](int k) {
        const Eigen::Vector3d u =
            rotation ? Eigen::Vector3d(*rotation * neutral.col(k)) : Eigen::Vector3d(neutral.col(k));
        return limit[k] - angle_between(axis.col(k), u);
    };
    if (!uniform) {
        for (int k = 0; k < STEWART_LEGS; ++k) keep_smallest(out, index, margin(k), k + 1, 0);
        return;
    }
    const int widest = static_cast<int>(std::min_element(cosine, cosine + STEWART_LEGS) - cosine);
    keep_smallest(out, index, margin(widest), widest + 1, 0);
}

}  // namespace

LimitConstants limit_constants(const stewart_params &p, const PlatformGeometry &geometry,
                               double warn_condition) {
    LimitConstants c;
    c.geometry = geometry;
    c.frames = frames_of(p);
    const Eigen::Vector3d home(0.0, 0.0, p.home_height);
    c.shortest_stroke_min = HUGE_VAL;
    c.longest_arm = 0.0;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Eigen::Vector3d leg = home + geometry.platform_points.col(k) - geometry.base_points.col(k);
        // A leg of zero length at home has no direction: z up stands in for it.
        const Eigen::Vector3d at_home = unit_or(leg.data(), 0, Eigen::Vector3d::UnitZ());
        c.base_neutral.col(k) = unit_or(p.base_joint_neutral, k, at_home);
        c.platform_neutral.col(k) = unit_or(p.platform_joint_neutral, k, at_home);
        c.stroke_min[k] = stroke_min_of(p, k);
        c.stroke_max[k] = stroke_max_of(p, k);
        c.base_joint_limit[k] = p.base_joint_limit;
        c.platform_joint_limit[k] = p.platform_joint_limit;
        c.shortest_stroke_min = std::min(c.shortest_stroke_min, c.stroke_min[k]);
        c.longest_arm = std::max(
            c.longest_arm, (geometry.platform_points.col(k) - c.frames.tool_origin).norm());
    }
    c.uniform_base_limit = std::equal(c.base_joint_limit + 1, c.base_joint_limit + STEWART_LEGS,
                                      c.base_joint_limit);
    c.uniform_platform_limit =
        std::equal(c.platform_joint_limit + 1, c.platform_joint_limit + STEWART_LEGS,
                   c.platform_joint_limit);
    c.leg_diameter = p.leg_diameter;
    c.warn_condition = warn_condition;
    return c;
}

double segment_distance_squared(const Eigen::Vector3d &p0, const Eigen::Vector3d &p1,
                                const Eigen::Vector3d &q0, const Eigen::Vector3d &q1) {
    // Minimise |r + s d1 - t d2|^2 over s, t in [0, 1]: the unconstrained s clamped, the best t
    // for it, and if that t is clamped, the best s for the clamped t.
    const Eigen::Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const double a = d1.squaredNorm(), e = d2.squaredNorm(), b = d1.dot(d2);
    const double c = d1.dot(r), f = d2.dot(r);
    const double tiny = 1e-300;
    double s, t;
    if (a <= tiny && e <= tiny) return r.squaredNorm();
    if (a <= tiny) {
        s = 0.0;
        t = std::clamp(f / e, 0.0, 1.0);
    } else if (e <= tiny) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
    } else {
        const double denominator = a * e - b * b;  // >= 0; 0 for parallel segments
        s = denominator > 0.0 ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
        t = (b * s + f) / e;
        if (t < 0.0) {
            t = 0.0;
            s = std::clamp(-c / a, 0.0, 1.0);
        } else if (t > 1.0) {
            t = 1.0;
            s = std::clamp((b - c) / a, 0.0, 1.0);
        }
    }
    return (r + s * d1 - t * d2).squaredNorm();
}

void check_limits(const LimitConstants &c, const double q[6], stewart_limits_output &out,
                  bool with_condition, double *inverse_norm) {
    if (c.frames.identity) return check_platform_limits(c, q, out, with_condition, inverse_norm);
    double platform[6];
    platform_pose(c.frames, q, nullptr, platform, nullptr);  // cannot fail without rates
    check_platform_limits(c, platform, out, with_condition, inverse_norm);
}

void check_platform_limits(const LimitConstants &c, const double q[6], stewart_limits_output &out,
                           bool with_condition, double *inverse_norm) {
    const PlatformGeometry &g = c.geometry;
    const Eigen::Matrix3d R = rotation_from_rpy(q[3], q[4], q[5]);
    const Eigen::Vector3d position(q[0], q[1], q[2]);
    for (int i = 0; i < STEWART_LIMIT_CLASSES; ++i) {
        out.margin[i] = HUGE_VAL;
        out.leg[i] = out.other_leg[i] = 0;
    }
    LegKinematics legs;
    legs.arm.noalias() = R * g.platform_points;
    Matrix36 top;  // platform joint centres, world
    double base_cos[STEWART_LEGS], platform_cos[STEWART_LEGS];  // of the angle to the neutral
    bool has_direction = true;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        top.col(k) = position + legs.arm.col(k);
        const Eigen::Vector3d d = top.col(k) - g.base_points.col(k);
        const double L = d.norm();
        keep_smallest(out, STEWART_LIMIT_STROKE - 1,
                      std::min(L - c.stroke_min[k], c.stroke_max[k] - L), k + 1, 0);
        // A leg of (nearly) zero length has no direction: its joints are as far out as can be.
        const bool defined = L > g.min_length;
        has_direction = has_direction && defined;
        const Eigen::Vector3d n = defined ? Eigen::Vector3d(d / L) : Eigen::Vector3d(-c.base_neutral.col(k));
        legs.axis.col(k) = n;
        legs.length[k] = L;
        base_cos[k] = n.dot(c.base_neutral.col(k));
        platform_cos[k] = n.dot(R * c.platform_neutral.col(k));
    }
    joint_margins(c.base_joint_limit, c.uniform_base_limit, legs.axis, c.base_neutral, nullptr,
                  base_cos, out, STEWART_LIMIT_BASE_JOINT - 1);
    joint_margins(c.platform_joint_limit, c.uniform_platform_limit, legs.axis,
                  c.platform_neutral, &R, platform_cos, out, STEWART_LIMIT_PLATFORM_JOINT - 1);
    // Every pair: legs that are not neighbours meet too when the platform turns far enough.
    // Neighbours first, then a pair only if the spheres around the two legs can be closer than
    // the closest pair so far.
    double closest = HUGE_VAL;
    for (const LegPair &pair : kPairs) {
        const int i = pair.first, j = pair.second;
        const Eigen::Vector3d middle_i = 0.5 * (g.base_points.col(i) + top.col(i));
        const Eigen::Vector3d middle_j = 0.5 * (g.base_points.col(j) + top.col(j));
        const double apart = (middle_i - middle_j).norm() - 0.5 * (legs.length[i] + legs.length[j]);
        if (apart >= closest) continue;
        const double d = std::sqrt(segment_distance_squared(g.base_points.col(i), top.col(i),
                                                            g.base_points.col(j), top.col(j)));
        if (d < closest) {
            closest = d;
            keep_smallest(out, STEWART_LIMIT_INTERFERENCE - 1, d - c.leg_diameter, i + 1, j + 1);
        }
    }
    double inverse_condition = 0.0;
    out.condition = HUGE_VAL;
    if (!with_condition) {
        out.condition = 0.0;
        inverse_condition = HUGE_VAL;
    } else if (has_direction) {
        LegJacobian J;
        leg_jacobian(g, legs, J);
        out.condition = J.condition;
        if (std::isfinite(J.condition) && J.condition > 0.0) {
            inverse_condition = 1.0 / J.condition;
            if (inverse_norm)
                *inverse_norm = J.inverse_transposed.cwiseAbs().rowwise().sum().maxCoeff();
        }
    }
    out.margin[STEWART_LIMIT_CONDITION - 1] = inverse_condition - 1.0 / c.warn_condition;
    classify_margins(out);
}

void classify_margins(stewart_limits_output &out) {
    out.first = STEWART_LIMIT_NONE;
    out.failed = 0;
    for (int i = STEWART_LIMIT_CLASSES - 1; i >= 0; --i)
        if (out.margin[i] < 0.0) {
            out.failed |= 1 << i;
            out.first = i + 1;
        }
}

}  // namespace stewart
