#include "limits/limit_check.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "kinematics/joints.hpp"
#include "kinematics/motion.hpp"
#include "util/message.hpp"
#include "util/range.hpp"

namespace stewart {

namespace {

// One stroke end per leg.
double stroke_min_of(const stewart_params &p, int leg) { return p.stroke_min[leg]; }
double stroke_max_of(const stewart_params &p, int leg) { return p.stroke_max[leg]; }

// Column k of an x1, y1, z1, ..., z6 array, made unit; the fallback if it is zero. Scaled by
// its largest component first, so that no length overflows (1e155) or underflows (1e-200).
Eigen::Vector3d unit_or(const double *xyz, int k, const Eigen::Vector3d &fallback) {
    Eigen::Vector3d v(xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]);
    const double largest = v.cwiseAbs().maxCoeff();
    if (!(largest > 0.0)) return fallback;
    v /= largest;
    return v / v.norm();
}

// The angle between two unit vectors, accurate near 0 and pi (acos is not).
double angle_between(const Eigen::Vector3d &u, const Eigen::Vector3d &v) {
    return std::atan2(u.cross(v).norm(), u.dot(v));
}

// Slack between cos(limit) and the cosine above which a joint is inside its limit for sure. The
// cosine c = fl(n . v) of the unit axis n = fl(d / L) and the unit neutral v (fl(neutral / norm),
// or R v with R from rotation_from_rpy): |n|, |v| and R's columns are unit to within 10 eps
// (eps = 2^-53), so the exact angle theta between n and v has cos(theta) >= c - 41 eps (the dot's
// rounding 3 eps, the norms' 3 x 10 eps, cos(limit)'s rounding eps) and, arccos falling at least
// as fast as its argument rises, theta <= limit - (slack - 41 eps). angle_between's atan2 of the
// rounded |n x v| and n . v (each off by at most 10 eps, |n||v| >= 0.99) is off theta by at most
// 20 eps + atan2's own ulp: the computed angle stays below the limit, margin >= 0, whenever
// c >= cos(limit) + slack with slack far above those 65 eps (1.4e-14 rad).
// tests/unit/test_limit_failures.cpp compares the verdicts on random poses near and far.
constexpr double kJointCosineSlack = 1e-9;
// A pair of legs whose sphere gap (sphere_gap) is at least the diameter plus this is measured by
// neither verdict of interference: far above the gap's and the distance's roundings [m].
constexpr double kInterferenceSlack = 1e-9;

// The cosine above which a joint of this limit is inside it for sure (see kJointCosineSlack).
double inside_cosine(double limit) {
    if (!(limit > 0.0)) return HUGE_VAL;  // fails at every angle (or NaN): never skipped
    if (limit >= M_PI) return -HUGE_VAL;  // atan2 never exceeds fl(pi): never fails
    return std::cos(limit) + kJointCosineSlack;
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
// largest angle needs its arc, unless every leg's margin is wanted (every_leg); the rotation
// turns platform-frame axes into the world.
void joint_margins(const double limit[STEWART_LEGS], bool uniform, const Matrix36 &axis,
                   const Matrix36 &neutral, const Eigen::Matrix3d *rotation,
                   const double cosine[STEWART_LEGS], stewart_limits_output &out, int index,
                   bool every_leg) {
    auto margin = [&](int k) {
        const Eigen::Vector3d u = rotation ? Eigen::Vector3d(*rotation * neutral.col(k))
                                           : Eigen::Vector3d(neutral.col(k));
        return limit[k] - angle_between(axis.col(k), u);
    };
    if (!uniform || every_leg) {
        for (int k = 0; k < STEWART_LEGS; ++k) {
            const double m = margin(k);
            if (every_leg) out.leg_margin[index][k] = m;
            keep_smallest(out, index, m, k + 1, 0);
        }
        return;
    }
    const int widest = static_cast<int>(std::min_element(cosine, cosine + STEWART_LEGS) - cosine);
    keep_smallest(out, index, margin(widest), widest + 1, 0);
}

}  // namespace

namespace {

// How thick the legs are at one side's joints: the body at the base and the rod at the platform
// for legs given as actuators, else leg_diameter.
double joint_thickness(const stewart_params &p, bool base) {
    if (!(p.leg_body_length > 0.0 || p.leg_rod_length > 0.0)) return p.leg_diameter;
    if (base) return p.leg_body_length > 0.0 ? p.leg_body_diameter : 0.0;
    return p.leg_rod_length > 0.0 ? p.leg_rod_diameter : 0.0;
}

// Two legs' joints a distance d apart are one joint of both (a 3-6 layout, as measured or
// calibrated: sockets on one ball) when d is within the legs' radius there (two legs could not
// be mounted so close otherwise), or below `coincident` for legs of no thickness; the legs are
// then not checked against each other.
bool one_joint(double d, double thickness, double coincident) {
    return d <= std::max(coincident, 0.5 * thickness);
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
    c.platform_radius = 0.0;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Eigen::Vector3d leg =
            home + geometry.platform_points.col(k) - geometry.base_points.col(k);
        // A leg of zero length at home has no direction: z up stands in for it.
        const Eigen::Vector3d at_home = unit_or(leg.data(), 0, Eigen::Vector3d::UnitZ());
        c.base_neutral.col(k) = unit_or(p.base_joint_neutral, k, at_home);
        c.platform_neutral.col(k) = unit_or(p.platform_joint_neutral, k, at_home);
        c.stroke_min[k] = stroke_min_of(p, k);
        c.stroke_max[k] = stroke_max_of(p, k);
        c.base_joint_limit[k] = p.base_joint_limit;
        c.platform_joint_limit[k] = p.platform_joint_limit;
        c.base_inside_cosine[k] = inside_cosine(c.base_joint_limit[k]);
        c.platform_inside_cosine[k] = inside_cosine(c.platform_joint_limit[k]);
        c.shortest_stroke_min = std::min(c.shortest_stroke_min, c.stroke_min[k]);
        c.platform_radius = std::max(c.platform_radius, geometry.platform_points.col(k).norm());
        c.longest_arm = std::max(c.longest_arm,
                                 (geometry.platform_points.col(k) - c.frames.tool_origin).norm());
    }
    c.uniform_base_limit =
        std::equal(c.base_joint_limit + 1, c.base_joint_limit + STEWART_LEGS, c.base_joint_limit);
    c.uniform_platform_limit =
        std::equal(c.platform_joint_limit + 1, c.platform_joint_limit + STEWART_LEGS,
                   c.platform_joint_limit);
    c.leg_diameter = p.leg_diameter;
    c.shaped = p.leg_body_length > 0.0 || p.leg_rod_length > 0.0;
    c.body_radius = p.leg_body_length > 0.0 ? 0.5 * p.leg_body_diameter : 0.0;
    c.body_length = p.leg_body_length;
    c.rod_radius = p.leg_rod_length > 0.0 ? 0.5 * p.leg_rod_diameter : 0.0;
    c.rod_length = p.leg_rod_length;
    c.interference_reach = c.shaped ? 2.0 * std::max(c.body_radius, c.rod_radius) : c.leg_diameter;
    for (int i = 0; i < STEWART_LEGS; ++i)
        for (int j = 0; j < STEWART_LEGS; ++j)
            c.shares_joint[i][j] =
                i != j &&
                (one_joint((geometry.base_points.col(i) - geometry.base_points.col(j)).norm(),
                           joint_thickness(p, true), geometry.min_length) ||
                 one_joint(
                     (geometry.platform_points.col(i) - geometry.platform_points.col(j)).norm(),
                     joint_thickness(p, false), geometry.min_length));
    for (int i = 0; i < 6; ++i) {
        c.axis_min[i] = p.axis_min[i];
        c.axis_max[i] = p.axis_max[i];
    }
    c.warn_condition = warn_condition;
    // The leg classes' limits, 0 (none) as +inf: a margin limit - |value| is then +inf.
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const double given[] = {p.leg_speed_max[k], p.leg_accel_max[k], p.leg_jerk_max[k],
                                p.leg_force_max[k]};
        for (int i = 0; i < 4; ++i) c.leg_limit[i][k] = given[i] > 0.0 ? given[i] : HUGE_VAL;
    }
    return c;
}

namespace {

// The shortest distance between two parts of legs (segments) less their radii.
double part_margin(const Eigen::Vector3d &p0, const Eigen::Vector3d &p1, double p_radius,
                   const Eigen::Vector3d &q0, const Eigen::Vector3d &q1, double q_radius) {
    return std::sqrt(segment_distance_squared(p0, p1, q0, q1)) - (p_radius + q_radius);
}

}  // namespace

double leg_pair_margin(const LimitConstants &c, int i, int j, const Matrix36 &top,
                       const Matrix36 &axis, const Vector6 &length) {
    const Matrix36 &base = c.geometry.base_points;
    if (c.shares_joint[i][j]) return HUGE_VAL;
    if (!c.shaped)
        return std::sqrt(segment_distance_squared(base.col(i), top.col(i), base.col(j),
                                                  top.col(j))) -
               c.leg_diameter;
    // Each part cut to its leg: a body reaches at most the platform joint, a rod the base joint.
    struct Part {
        Eigen::Vector3d from, to;
        double radius;
    };
    auto parts = [&](int k, Part out[2]) {
        int n = 0;
        if (c.body_length > 0.0)
            out[n++] = {
                base.col(k),
                Eigen::Vector3d(base.col(k) + std::min(c.body_length, length[k]) * axis.col(k)),
                c.body_radius};
        if (c.rod_length > 0.0)
            out[n++] = {
                Eigen::Vector3d(top.col(k) - std::min(c.rod_length, length[k]) * axis.col(k)),
                top.col(k), c.rod_radius};
        return n;
    };
    Part a[2], b[2];
    const int na = parts(i, a), nb = parts(j, b);
    double margin = HUGE_VAL;
    for (int x = 0; x < na; ++x)
        for (int y = 0; y < nb; ++y)
            margin = std::min(margin, part_margin(a[x].from, a[x].to, a[x].radius, b[y].from,
                                                  b[y].to, b[y].radius));
    return margin;
}

double axis_limit_margin(const LimitConstants &c, const double q[6], int *axis) {
    // Metres and radians compare through the arm: an angle's margin counts as the way the
    // farthest platform joint moves through it, so the axis named is the nearest to its limit
    // in one unit; the margin returned stays in its axis' own unit.
    const double arm = c.longest_arm > 0.0 ? c.longest_arm : 1.0;
    double margin = HUGE_VAL, nearest = HUGE_VAL;
    *axis = 0;
    for (int i = 0; i < 6; ++i) {
        const double m = std::min(q[i] - c.axis_min[i], c.axis_max[i] - q[i]);
        const double way = i < 3 || m > 0.5 * DBL_MAX ? m : m * arm;  // no limit: as is
        if (way < nearest) {
            nearest = way;
            margin = m;
            *axis = i + 1;
        }
    }
    return margin;
}

stewart_status check_limit_parameters(const stewart_params &p, char *msg, size_t size) {
    static const char *const kAxes[] = {"x", "y", "z", "roll", "pitch", "yaw"};
    for (int i = 0; i < 6; ++i)
        if (!(p.axis_min[i] <= p.axis_max[i]))
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "software position limits of %s: axis_min[%d] = %s must not be "
                               "above axis_max[%d] = %s",
                               kAxes[i], i + 1, ExactText(p.axis_min[i]).c_str(), i + 1,
                               ExactText(p.axis_max[i]).c_str());
    const struct {
        const char *name;
        const double *xyz;
    } neutrals[] = {{"base_joint_neutral", p.base_joint_neutral},
                    {"platform_joint_neutral", p.platform_joint_neutral}};
    for (const auto &n : neutrals)
        for (int k = 0; k < STEWART_LEGS; ++k) {
            const double *v = n.xyz + 3 * k;
            const double largest = std::max({std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2])});
            if (largest == 0.0 || largest >= DBL_MIN) continue;
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "%s[%d..%d] = (%s, %s, %s) of leg %d is too small to give a "
                               "direction (every component below %g, where doubles lose "
                               "digits): give the axis at any ordinary length, or zero for "
                               "the leg's direction at home",
                               n.name, 3 * k + 1, 3 * k + 3, ExactText(v[0]).c_str(),
                               ExactText(v[1]).c_str(), ExactText(v[2]).c_str(), k + 1, DBL_MIN);
        }
    const JointGeometry g = joint_geometry(p);
    const bool shaped = p.leg_body_length > 0.0 || p.leg_rod_length > 0.0;
    const double coincident = 1e-12 * (g.base_size + g.platform_size);
    struct Side {
        const char *name;
        const Matrix36 &points;
        double thickness;
        const char *field;
    };
    const Side sides[] = {{"base", g.base_points, joint_thickness(p, true),
                           shaped ? "leg_body_diameter" : "leg_diameter"},
                          {"platform", g.platform_points, joint_thickness(p, false),
                           shaped ? "leg_rod_diameter" : "leg_diameter"}};
    for (const Side &side : sides) {
        if (!(side.thickness > 0.0)) continue;
        for (int i = 0; i < STEWART_LEGS; ++i)
            for (int j = i + 1; j < STEWART_LEGS; ++j) {
                const double d = (side.points.col(i) - side.points.col(j)).norm();
                if (one_joint(d, side.thickness, coincident) || d > side.thickness)
                    continue;  // one joint of two legs, or apart
                return set_message(msg, size, STEWART_ERR_PARAMETER,
                                   "the %s joints of legs %d and %d are %s m apart, not farther "
                                   "than the legs are thick there (%s = %s m): the legs would "
                                   "interfere at every pose; move the joints apart or give the "
                                   "legs' real diameter",
                                   side.name, i + 1, j + 1, ExactText(d).c_str(), side.field,
                                   ExactText(side.thickness).c_str());
            }
    }
    return STEWART_OK;
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
    double platform[6];
    if (c.frames.identity) std::copy(q, q + 6, platform);
    else platform_pose(c.frames, q, nullptr, platform, nullptr);  // cannot fail without rates
    check_platform_limits(c, platform, out, with_condition, inverse_norm, true);
    const int axis = STEWART_LIMIT_AXIS - 1;
    out.margin[axis] = axis_limit_margin(c, q, &out.leg[axis]);
    std::fill(out.leg_margin[axis], out.leg_margin[axis] + STEWART_LEGS, out.margin[axis]);
    classify_margins(c, out);
}

namespace {

// What both checks need at the platform's pose q: the rotation, the legs (arms, unit axes,
// lengths), the platform joint centres and the legs' midpoints, each leg's cosine to its neutral
// axes; has_direction false if a leg has none (length <= min_length: its axis is then minus the
// base neutral).
struct PlatformLegs {
    Eigen::Matrix3d R;
    LegKinematics legs;
    Matrix36 top;                                               // platform joint centres, world
    Matrix36 middle;                                            // the legs' midpoints, world
    double base_cos[STEWART_LEGS], platform_cos[STEWART_LEGS];  // of the angle to the neutral
    bool has_direction;
};

// PlatformLegs at the platform's position and rotation (base frame).
void platform_legs(const LimitConstants &c, const Eigen::Vector3d &position,
                   const Eigen::Matrix3d &rotation, PlatformLegs &l) {
    const PlatformGeometry &g = c.geometry;
    l.R = rotation;
    l.legs.arm.noalias() = l.R * g.platform_points;
    l.has_direction = true;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        l.top.col(k) = position + l.legs.arm.col(k);
        l.middle.col(k) = 0.5 * (g.base_points.col(k) + l.top.col(k));
        const Eigen::Vector3d d = l.top.col(k) - g.base_points.col(k);
        const double L = d.norm();
        // A leg of (nearly) zero length has no direction: its joints are as far out as can be.
        const bool defined = L > g.min_length;
        l.has_direction = l.has_direction && defined;
        const Eigen::Vector3d n =
            defined ? Eigen::Vector3d(d / L) : Eigen::Vector3d(-c.base_neutral.col(k));
        l.legs.axis.col(k) = n;
        l.legs.length[k] = L;
        l.base_cos[k] = n.dot(c.base_neutral.col(k));
        l.platform_cos[k] = n.dot(l.R * c.platform_neutral.col(k));
    }
}

// PlatformLegs at the platform's pose q (base frame; roll, pitch, yaw).
void platform_legs(const LimitConstants &c, const double q[6], PlatformLegs &l) {
    platform_legs(c, Eigen::Vector3d(q[0], q[1], q[2]), rotation_from_rpy(q[3], q[4], q[5]), l);
}

// The sphere bound: the two legs' segments are at least this far apart (their midpoints'
// distance less both half lengths); a pair is measured only if it may beat `closest`.
double sphere_gap(const PlatformLegs &l, int i, int j) {
    return (l.middle.col(i) - l.middle.col(j)).norm() - 0.5 * (l.legs.length[i] + l.legs.length[j]);
}

// The interference margin of legs i and j.
double leg_margin(const LimitConstants &c, const PlatformLegs &l, int i, int j) {
    return leg_pair_margin(c, i, j, l.top, l.legs.axis, l.legs.length);
}

// True if a joint class fails: joint_margins' verdict, the arc only where the cosine leaves
// doubt (below `inside`; with one limit only the widest leg's, as joint_margins).
bool joint_fails(const double limit[STEWART_LEGS], const double inside[STEWART_LEGS], bool uniform,
                 const Matrix36 &axis, const Matrix36 &neutral, const Eigen::Matrix3d *rotation,
                 const double cosine[STEWART_LEGS]) {
    auto fails = [&](int k) {
        if (cosine[k] >= inside[k]) return false;
        const Eigen::Vector3d u = rotation ? Eigen::Vector3d(*rotation * neutral.col(k))
                                           : Eigen::Vector3d(neutral.col(k));
        return limit[k] - angle_between(axis.col(k), u) < 0.0;
    };
    if (uniform)
        return fails(static_cast<int>(std::min_element(cosine, cosine + STEWART_LEGS) - cosine));
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (fails(k)) return true;
    return false;
}

}  // namespace

namespace {

// The exact verdicts at the pose (platform_limit_failures' body); if found is given and nothing
// fails, what the clearance needs: the smallest cosine above its inside cosine, distance (or
// sphere gap) above the diameter and leg length.
int limit_failures(const LimitConstants &c, const Eigen::Vector3d &position,
                   const Eigen::Matrix3d &rotation, LimitClearance *found) {
    PlatformLegs l;
    platform_legs(c, position, rotation, l);
    int failed = 0;
    if (joint_fails(c.base_joint_limit, c.base_inside_cosine, c.uniform_base_limit, l.legs.axis,
                    c.base_neutral, nullptr, l.base_cos))
        failed |= 1 << (STEWART_LIMIT_BASE_JOINT - 1);
    if (joint_fails(c.platform_joint_limit, c.platform_inside_cosine, c.uniform_platform_limit,
                    l.legs.axis, c.platform_neutral, &l.R, l.platform_cos))
        failed |= 1 << (STEWART_LIMIT_PLATFORM_JOINT - 1);
    // Interference: some pair closer than the diameter. A pair whose spheres are at least
    // kInterferenceSlack beyond the diameter apart cannot be (the sphere gap is a lower bound of
    // the distance, both computed to about 1e-15 m), so only the others are measured; the full
    // check's smallest distance is below the diameter exactly when one of them is, except at
    // rounding distance from it (test_limit_failures: the same verdicts on the edge).
    const double near = c.interference_reach + kInterferenceSlack;
    const bool checked = c.interference_reach > 0.0;
    double closest = HUGE_VAL;  // the margin or sphere gap less the reach of each pair, smallest
    bool numbers = true;        // no NaN among them (a NaN clears nothing)
    for (const LegPair &pair : kPairs) {
        if (c.shares_joint[pair.first][pair.second]) continue;
        const double gap = sphere_gap(l, pair.first, pair.second);
        if (!(gap < near)) {
            numbers = numbers && gap == gap;
            closest = std::min(closest, gap - c.interference_reach);
            continue;
        }
        const double margin = leg_margin(c, l, pair.first, pair.second);
        if (margin < 0.0 || (checked && margin == 0.0))
            return failed | 1 << (STEWART_LIMIT_INTERFERENCE - 1);
        numbers = numbers && margin == margin;
        closest = std::min(closest, margin);
    }
    if (found && failed == 0) {
        found->joint_cosine = found->shortest_leg = HUGE_VAL;
        for (int k = 0; k < STEWART_LEGS; ++k) {
            const double base = l.base_cos[k] - c.base_inside_cosine[k],
                         platform = l.platform_cos[k] - c.platform_inside_cosine[k];
            numbers = numbers && base == base && platform == platform &&
                      l.legs.length[k] == l.legs.length[k];
            found->joint_cosine = std::min({found->joint_cosine, base, platform});
            found->shortest_leg = std::min(found->shortest_leg, l.legs.length[k]);
        }
        found->interference = closest;
        found->valid = numbers && found->interference == found->interference;
    }
    return failed;
}

// Far above the roundings of the cosines, distances and lengths the clearance compares (about
// 1e-15 of quantities near 1) [m, or a cosine's unit].
constexpr double kClearanceSlack = 1e-9;

}  // namespace

int platform_limit_failures(const LimitConstants &c, const Eigen::Vector3d &position,
                            const Eigen::Matrix3d &rotation) {
    return limit_failures(c, position, rotation, nullptr);
}

// The bound. From the clearance's pose to this one, every platform joint b_k moved by at most
// delta = |dp| + |dR|_F |b_k| (|dR|_2 <= |dR|_F), so each leg vector d_k = p + R b_k - a_k by
// at most delta, and its unit axis n_k = d_k / |d_k| by at most 2 delta / |d_k| (at the old
// length). A base joint's cosine n . v moves by at most that, a platform joint's n . R v by that
// plus |dR|_2. Each point of a leg's segment moves by at most delta, so a pair's distance and its
// sphere gap (midpoints' distance less the half lengths) move by at most 2 delta. So when the
// clearances exceed these moves (and the roundings: kClearanceSlack), every cosine is still at or
// above its inside cosine (no arc measured, no joint fails), every pair's sphere gap is still
// above the diameter's slack or its distance above the diameter, and every leg keeps a
// direction: the exact check would find nothing, as this returns. tests/unit/
// test_limit_failures.cpp compares it with the exact verdict along random walks through the
// limits (test_clearance) and at the farthest poses it spares (test_clearance_edge).
namespace {

// clearance_spares' body, inlined into the plant's check (as it was before the test wanted it).
inline bool spares(const LimitConstants &c, const LimitClearance &clearance,
                   const Eigen::Vector3d &position, const Eigen::Matrix3d &rotation) {
    if (!clearance.valid) return false;
    const double moved = (position - clearance.position).norm();
    const double turned = (rotation - clearance.rotation).norm();  // Frobenius
    const double delta = moved + turned * c.platform_radius;
    const double shortest = clearance.shortest_leg - delta;
    // A shaped leg's parts end at points a + f d (f = min(length, L) / L), which move by at
    // most 2 delta: twice a segment's points.
    const double pair_motion = (c.shaped ? 4.0 : 2.0) * delta;
    return shortest > c.geometry.min_length + kClearanceSlack &&
           clearance.interference >= pair_motion + kClearanceSlack &&
           clearance.joint_cosine >=
               2.0 * delta / clearance.shortest_leg + turned + kClearanceSlack;
}

}  // namespace

bool clearance_spares(const LimitConstants &c, const LimitClearance &clearance,
                      const Eigen::Vector3d &position, const Eigen::Matrix3d &rotation) {
    return spares(c, clearance, position, rotation);
}

int platform_limit_failures(const LimitConstants &c, const Eigen::Vector3d &position,
                            const Eigen::Matrix3d &rotation, LimitClearance &clearance) {
    if (spares(c, clearance, position, rotation)) return 0;
    LimitClearance found;
    const int failed = limit_failures(c, position, rotation, &found);
    clearance = found;
    clearance.valid = failed == 0 && found.valid && position.allFinite() && rotation.allFinite();
    clearance.position = position;
    clearance.rotation = rotation;
    return failed;
}

int platform_limit_failures(const LimitConstants &c, const double q[6]) {
    return platform_limit_failures(c, Eigen::Vector3d(q[0], q[1], q[2]),
                                   rotation_from_rpy(q[3], q[4], q[5]));
}

void check_platform_limits(const LimitConstants &c, const double q[6], stewart_limits_output &out,
                           bool with_condition, double *inverse_norm, bool every_leg) {
    const PlatformGeometry &g = c.geometry;
    for (int i = 0; i < STEWART_LIMIT_CLASSES; ++i) {
        out.margin[i] = HUGE_VAL;
        out.leg[i] = out.other_leg[i] = 0;
        if (every_leg) std::fill(out.leg_margin[i], out.leg_margin[i] + STEWART_LEGS, HUGE_VAL);
    }
    PlatformLegs l;
    platform_legs(c, q, l);
    const LegKinematics &legs = l.legs;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const double m =
            std::min(legs.length[k] - c.stroke_min[k], c.stroke_max[k] - legs.length[k]);
        if (every_leg) out.leg_margin[STEWART_LIMIT_STROKE - 1][k] = m;
        keep_smallest(out, STEWART_LIMIT_STROKE - 1, m, k + 1, 0);
    }
    joint_margins(c.base_joint_limit, c.uniform_base_limit, legs.axis, c.base_neutral, nullptr,
                  l.base_cos, out, STEWART_LIMIT_BASE_JOINT - 1, every_leg);
    joint_margins(c.platform_joint_limit, c.uniform_platform_limit, legs.axis, c.platform_neutral,
                  &l.R, l.platform_cos, out, STEWART_LIMIT_PLATFORM_JOINT - 1, every_leg);
    // Every pair: legs that are not neighbours meet too when the platform turns far enough.
    // Neighbours first, then a pair only if the spheres around the two legs can be closer than
    // the closest pair so far (every_leg: than the closest pair so far of either leg).
    // Unshaped legs compare distances (margin + leg_diameter), shaped ones margins, each with
    // the sphere gap less the same reach.
    const double reach = c.shaped ? c.interference_reach : 0.0;
    const double offset = c.shaped ? 0.0 : c.leg_diameter;
    const int interference = STEWART_LIMIT_INTERFERENCE - 1;
    double closest = HUGE_VAL;
    double leg_closest[STEWART_LEGS], leg_margin_of[STEWART_LEGS];  // per leg: d, its margin
    std::fill(leg_closest, leg_closest + STEWART_LEGS, HUGE_VAL);
    std::fill(leg_margin_of, leg_margin_of + STEWART_LEGS, HUGE_VAL);
    for (const LegPair &pair : kPairs) {
        const int i = pair.first, j = pair.second;
        if (c.shares_joint[i][j]) continue;
        const double bound = every_leg ? std::max(leg_closest[i], leg_closest[j]) : closest;
        if (sphere_gap(l, i, j) - reach >= bound) continue;
        const double margin = leg_margin(c, l, i, j);
        const double d = margin + offset;
        for (int k : {i, j})
            if (d < leg_closest[k]) leg_closest[k] = d, leg_margin_of[k] = margin;
        if (d < closest) {
            closest = d;
            keep_smallest(out, interference, margin, i + 1, j + 1);
        }
    }
    if (every_leg)
        std::copy(leg_margin_of, leg_margin_of + STEWART_LEGS, out.leg_margin[interference]);
    const bool has_direction = l.has_direction;
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
    const int condition = STEWART_LIMIT_CONDITION - 1;
    out.margin[condition] = inverse_condition - 1.0 / c.warn_condition;
    if (every_leg)
        std::fill(out.leg_margin[condition], out.leg_margin[condition] + STEWART_LEGS,
                  out.margin[condition]);
    classify_margins(c, out);
}

void classify_margins(const LimitConstants &c, stewart_limits_output &out) {
    out.first = STEWART_LIMIT_NONE;
    out.failed = 0;
    const int interference = STEWART_LIMIT_INTERFERENCE - 1;
    const bool touching = c.interference_reach > 0.0;  // legs of no thickness never touch
    for (int i = STEWART_LIMIT_CLASSES - 1; i >= 0; --i)
        if (out.margin[i] < 0.0 || (touching && i == interference && out.margin[i] == 0.0)) {
            out.failed |= 1 << i;
            out.first = i + 1;
        }
}

}  // namespace stewart
