#include "limits/range_bounds.hpp"

#include <algorithm>
#include <cmath>

namespace stewart {

RangeConstants range_constants(const LimitConstants &c) {
    RangeConstants rc;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        rc.cos_base_limit[k] = std::cos(c.base_joint_limit[k]);
        rc.cos_platform_limit[k] = std::cos(c.platform_joint_limit[k]);
        rc.base_can_fail[k] = c.base_joint_limit[k] < M_PI;
        rc.platform_can_fail[k] = c.platform_joint_limit[k] < M_PI;
    }
    return rc;
}

// With d = L u (|d'| <= v, |d''| <= a; a turn: a = v): |u'| = v sin(phi) / L (phi: between d'
// and u), and u'' = (P d'' - L |u'|^2 u - 2 L' u') / L with L' = v cos(phi) and u' normal to
// u, so |u''| <= a / L + (v / L)^2 sin(phi) sqrt(sin^2(phi) + 4 cos^2(phi))
// <= a / L + (2 / sqrt(3)) (v / L)^2 (the maximum over phi).
void leg_rates(const LimitConstants &c, const LegState &legs, const AxisMotion &m, LegRates &out) {
    const double bend_factor = 2.0 / std::sqrt(3.0);
    out.reach = HUGE_VAL;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Eigen::Vector3d u = legs.kinematics.axis.col(k);
        const Eigen::Vector3d v = point_velocity(m, legs.top.col(k));
        const double length = legs.kinematics.length[k];
        out.turn_rate.col(k) = (v - u * u.dot(v)) / length;
        const double speed = m.rotation ? v.norm() : 1.0;  // a turn keeps the distance to its axis
        double shortest = std::max(c.stroke_min[k], c.geometry.min_length);
        // A short stroke_min bounds nothing: half the length now holds over a shorter way.
        if (0.5 * length > shortest) {
            shortest = 0.5 * length;
            if (speed > 0.0) out.reach = std::min(out.reach, shortest / speed);
        }
        out.speed[k] = speed;
        out.turn[k] = speed / shortest;
        out.bend[k] =
            bend_factor * out.turn[k] * out.turn[k] + (m.rotation ? speed : 0.0) / shortest;
    }
}

double taylor_radius(double g, double slope, double curvature) {
    if (!(g > 0.0)) return 0.0;
    if (!(curvature > 0.0)) return slope >= 0.0 ? HUGE_VAL : g / -slope;
    const double root = std::sqrt(slope * slope + 2.0 * curvature * g);
    return slope > 0.0 ? (slope + root) / curvature : 2.0 * g / (root - slope);
}

double joint_radius(const LimitConstants &c, const RangeConstants &rc, const LegState &legs,
                    const LegRates &rates, const AxisMotion &m, Holder &holder) {
    double radius = HUGE_VAL;
    auto keep = [&](double r, int limit, int k) {
        if (r < radius) {
            radius = r;
            holder = {limit, k + 1, 0};
        }
    };
    const double spin = m.rotation ? 1.0 : 0.0;  // how fast the platform's neutral axes turn
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Eigen::Vector3d u = legs.kinematics.axis.col(k), du = rates.turn_rate.col(k);
        if (rc.base_can_fail[k]) {
            const Eigen::Vector3d n = c.base_neutral.col(k);
            keep(taylor_radius(u.dot(n) - rc.cos_base_limit[k], du.dot(n), rates.bend[k]),
                 STEWART_LIMIT_BASE_JOINT, k);
        }
        if (rc.platform_can_fail[k]) {
            // (u . n)'' = u'' . n + 2 u' . n' + u . n'' with |n'|, |n''| <= spin.
            const Eigen::Vector3d n = legs.rotation * c.platform_neutral.col(k);
            const double n_rate = m.rotation ? u.dot(m.direction.cross(n)) : 0.0;
            const double curvature = rates.bend[k] + spin * (2.0 * rates.turn[k] + 1.0);
            keep(taylor_radius(u.dot(n) - rc.cos_platform_limit[k], du.dot(n) + n_rate, curvature),
                 STEWART_LIMIT_PLATFORM_JOINT, k);
        }
    }
    return radius;
}

namespace {

// The margin of one pair of legs at `legs`.
double pair_margin(const LimitConstants &c, const LegState &legs, int i, int j) {
    return leg_pair_margin(c, i, j, legs.top, legs.kinematics.axis, legs.kinematics.length);
}

}  // namespace

void pair_margins(const LimitConstants &c, const LegState &legs, double margin[kLegPairs]) {
    int p = 0;
    for (int i = 0; i < STEWART_LEGS; ++i)
        for (int j = i + 1; j < STEWART_LEGS; ++j) margin[p++] = pair_margin(c, legs, i, j);
}

void pair_bounds(const LimitConstants &c, const LegState &legs, const LegRates &rates,
                 const AxisMotion &m, const double margin[kLegPairs], PairBounds &out) {
    int p = 0;
    for (int i = 0; i < STEWART_LEGS; ++i)
        for (int j = i + 1; j < STEWART_LEGS; ++j, ++p) {
            // Points s and u of the two legs move apart at |s v_i - u v_j|: for a translation
            // |s - u| <= 1; for a turn |w x (s r_i - u r_j)|, convex in (s, u), so at most its
            // value at a corner of [0, 1]^2. A turn keeps every such length.
            // A shaped leg's part ends at a + f d (f = min(length, L) / L), moving at
            // |f d' + f' d| <= 2 |d'|: two legs' parts part at most 2 (v_i + v_j).
            const double rate =
                c.shaped ? 2.0 * (rates.speed[i] + rates.speed[j])
                : m.rotation
                    ? std::max({rates.speed[i], rates.speed[j],
                                m.direction.cross(legs.top.col(i) - legs.top.col(j)).norm()})
                    : 1.0;
            out.rate[p] = std::max(rate, 1e-300);  // two joints on the axis: cannot close
            out.margin[p] = margin[p];
            out.at[p] = 0.0;
        }
}

double interference_radius(const LimitConstants &c, const LegState &legs, double t, double cap,
                           PairBounds &pairs, Holder &holder) {
    if (!(c.interference_reach > 0.0)) return HUGE_VAL;
    double radius = cap;
    int p = 0;
    for (int i = 0; i < STEWART_LEGS; ++i)
        for (int j = i + 1; j < STEWART_LEGS; ++j, ++p) {
            const double rate = pairs.rate[p];
            if (pairs.margin[p] - rate * (t - pairs.at[p]) >= radius * rate) continue;
            pairs.margin[p] = pair_margin(c, legs, i, j);
            pairs.at[p] = t;
            const double r = std::max(0.0, pairs.margin[p]) / rate;
            if (r < radius) {
                radius = r;
                holder = {STEWART_LIMIT_INTERFERENCE, i + 1, j + 1};
            }
        }
    return radius;
}

double condition_radius(const LimitConstants &c, const LegState &legs, const LegRates &rates,
                        const LegJacobian &jacobian, const AxisMotion &m) {
    const double condition = jacobian.condition, warn = c.warn_condition;
    const double room = 1.0 - condition / warn;  // > 0 within the limit
    if (!legs.has_direction || !std::isfinite(condition) || !(room > 0.0)) return 0.0;
    const double inverse_size = 1.0 / c.geometry.characteristic_length;
    const double spin = m.rotation ? 1.0 : 0.0;  // |arm'| <= spin |arm|, |arm''| <= spin |arm|
    Matrix6 rate;  // D = dJ^T/dt: column k = (u', (arm' x u + arm x u') / length)
    double speed = 0.0, curvature = 0.0;  // S and M: sums over the columns of entry bounds
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Eigen::Vector3d u = legs.kinematics.axis.col(k), arm = legs.kinematics.arm.col(k);
        const Eigen::Vector3d du = rates.turn_rate.col(k);
        const Eigen::Vector3d darm =
            m.rotation ? Eigen::Vector3d(m.direction.cross(arm)) : Eigen::Vector3d::Zero();
        rate.block<3, 1>(0, k) = du;
        rate.block<3, 1>(3, k) = (darm.cross(u) + arm.cross(du)) * inverse_size;
        const double r = arm.norm() * inverse_size;
        speed += std::max(rates.turn[k], r * (spin + rates.turn[k]));
        curvature +=
            std::max(rates.bend[k], r * (spin + 2.0 * spin * rates.turn[k] + rates.bend[k]));
    }
    const auto infinity_norm = [](const Matrix6 &a) {
        return a.cwiseAbs().rowwise().sum().maxCoeff();
    };
    const double inverse_norm = infinity_norm(jacobian.inverse_transposed);  // b
    // J^T(t + h) is J^T (I + X) with X = J^-T (h D + R), or (I + Z) J^T with Z = (h D + R)
    // J^-T: either bounds ||J^-T(t + h)|| by ||J^-T|| / (1 - ||X or Z||), so the smaller rate
    // serves (near parallel legs one can be far below the other).
    const Matrix6 right = jacobian.inverse_transposed * rate;  // J^-T D
    const Matrix6 left = rate * jacobian.inverse_transposed;   // D J^-T
    // (b M / 2) h^2 + (g + S b / w) h - (1 - cond / w) <= 0, g = min(||J^-T D||, ||D J^-T||).
    const double linear =
        std::min(infinity_norm(right), infinity_norm(left)) + speed * inverse_norm / warn;
    const double quadratic = inverse_norm * curvature;
    return 2.0 * room / (linear + std::sqrt(linear * linear + 2.0 * quadratic * room));
}

}  // namespace stewart
