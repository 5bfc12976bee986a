#include "limits/axis_ranges.hpp"

#include <algorithm>
#include <cmath>

namespace stewart {

namespace {

constexpr double kSmallestStep = 1e-5;        // [m or rad]: a thinner excursion may be missed
constexpr double kConditionStep = 0.05;       // largest step for the condition [rad, or x the
                                              // platform's size for a translation]
// Bounds on the evaluations of one side: a march that has not met a limit by then ends there
// (reported as the search's end, STEWART_LIMIT_NONE).
constexpr int kMaxMarch = 2000, kMaxRefine = 80;

bool within(const stewart_limits_output &o) { return o.failed == 0; }

// The class whose margin a bracket's root is sought on: the first failing one.
int failing_index(const stewart_limits_output &o) { return o.first - 1; }

struct Search {
    const LimitConstants &c;
    double q[6];
    int axis;
    double sign;
    double extent;         // the farthest t searched
    double speed;          // bound on a platform joint's speed per unit t [m]
    double condition_cap;  // largest step where the condition leads

    // Where the condition was last computed, its value and ||J^-T||_inf there (cond = ||J^T||
    // ||J^-T||). A step of d changes each leg's column of J^T by at most d k_col (see at()).
    double reference_t = 0.0, reference_condition = HUGE_VAL, reference_inverse_norm = HUGE_VAL;
    double column_rate = HUGE_VAL;

    // The check at t; the condition only where it may have reached its limit since the
    // reference: with ||dJ^T||_inf <= e = 6 k_col |t - t_ref| and b = ||J^-T|| there,
    // cond <= (||J^T|| + e) b / (1 - b e), within the limit w while e b (1 + w) < w - cond_ref.
    void at(double t, stewart_limits_output &o) {
        double p[6];
        std::copy(q, q + 6, p);
        p[axis] += sign * t;
        const double e = 6.0 * column_rate * std::fabs(t - reference_t);
        const bool with_condition = !(e * reference_inverse_norm * (1.0 + c.warn_condition) <
                                      c.warn_condition - reference_condition);
        double inverse_norm = HUGE_VAL;
        check_limits(c, p, o, with_condition, &inverse_norm);
        if (with_condition) {
            reference_t = t;
            reference_condition = o.condition;
            reference_inverse_norm = inverse_norm;
        }
    }

    // A step along which no class with a known speed bound can reach its limit: each margin
    // divided by the fastest its class can change (stroke: a joint's speed; joint angles: that
    // over the shortest leg within the stroke, plus the platform's own turn for its joints;
    // interference: both legs' speeds). The closest class may step further, to beyond the
    // root its secant predicts: overshooting it only brackets the end sooner. The condition
    // has no bound: its secant and a cap stand in.
    double step(const stewart_limits_output &now, const stewart_limits_output &before,
                double last_step) const {
        const bool rotation = axis >= 3;
        const double joint_rate = speed / c.shortest_stroke_min;
        double safe[STEWART_LIMIT_CLASSES];
        safe[0] = now.margin[0] / speed;
        safe[1] = now.margin[1] / joint_rate;
        safe[2] = now.margin[2] / (joint_rate + (rotation ? 1.0 : 0.0));
        safe[3] = now.margin[3] / (2.0 * speed);
        double predicted[STEWART_LIMIT_CLASSES];
        for (int i = 0; i < STEWART_LIMIT_CLASSES; ++i) {
            const double slope = last_step > 0.0 ? (before.margin[i] - now.margin[i]) / last_step : 0.0;
            predicted[i] = slope > 0.0 ? now.margin[i] / slope : HUGE_VAL;
        }
        safe[4] = std::min(condition_cap, 0.5 * predicted[4]);
        const int closest = static_cast<int>(std::min_element(safe, safe + STEWART_LIMIT_CLASSES) - safe);
        // The condition's cap holds unless its own root is predicted within it.
        const bool overshoot = closest != STEWART_LIMIT_CONDITION - 1 || predicted[closest] <= condition_cap;
        double h = HUGE_VAL;
        for (int i = 0; i < STEWART_LIMIT_CLASSES; ++i)
            h = std::min(h, i == closest && overshoot ? std::max(safe[i], 1.25 * predicted[i]) : safe[i]);
        return std::max(h, kSmallestStep);
    }

    // t of the last pose within every limit (from `here`, the check at t = 0), and the first
    // limit's report beyond it.
    double run(const stewart_limits_output &here, double here_inverse_norm,
               stewart_limits_output &beyond) {
        stewart_limits_output ok = here, before = here;
        reference_condition = here.condition;
        reference_inverse_norm = here_inverse_norm;
        // A leg's unit vector turns at most speed / L (L >= the shortest stroke_min within the
        // stroke); its moment arm R b_k turns with the platform (rotations).
        const double turn = speed / c.shortest_stroke_min;
        column_rate = turn + ((axis >= 3 ? c.longest_arm : 0.0) + c.longest_arm * turn) /
                                 c.geometry.characteristic_length;
        double t_ok = 0.0, last_step = 0.0;
        for (int n = 0; n < kMaxMarch; ++n) {
            if (t_ok >= extent) break;
            const double h = std::min(step(ok, before, last_step), extent - t_ok);
            stewart_limits_output next;
            at(t_ok + h, next);
            if (!within(next)) {
                beyond = next;
                return refine(t_ok, ok, t_ok + h, beyond);
            }
            before = ok;
            ok = next;
            t_ok += h;
            last_step = h;
        }
        beyond = ok;
        beyond.first = STEWART_LIMIT_NONE;
        return std::min(t_ok, extent);
    }

    // Illinois regula falsi on the failing class's margin, bisection when it stalls, until the
    // bracket [t_ok, t_bad] is narrower than the tolerance.
    double refine(double t_ok, stewart_limits_output ok, double t_bad, stewart_limits_output &bad) {
        const double tol = kAxisRangeTolerance;
        double width_two_before = HUGE_VAL, width_before = HUGE_VAL;
        double weight_ok = 1.0, weight_bad = 1.0;
        int last_side = 0;
        for (int n = 0; n < kMaxRefine && t_bad - t_ok > tol; ++n) {
            const int i = failing_index(bad);
            const double m_ok = ok.margin[i] * weight_ok, m_bad = bad.margin[i] * weight_bad;
            const double width = t_bad - t_ok;
            const bool stalled = width > 0.5 * width_two_before;
            double t = stalled || !(m_ok > m_bad) ? t_ok + 0.5 * width
                                                  : t_ok + width * m_ok / (m_ok - m_bad);
            t = std::clamp(t, t_ok + 0.25 * tol, t_bad - 0.25 * tol);
            width_two_before = stalled ? HUGE_VAL : width_before;
            width_before = width;
            stewart_limits_output o;
            at(t, o);
            if (within(o)) {
                t_ok = t;
                ok = o;
                weight_ok = 1.0;
                weight_bad = last_side == 1 ? 0.5 * weight_bad : 1.0;
                last_side = 1;
            } else {
                const bool same_class = o.first == bad.first;
                t_bad = t;
                bad = o;
                weight_bad = 1.0;
                weight_ok = last_side == -1 && same_class ? 0.5 * weight_ok : 1.0;
                last_side = -1;
            }
        }
        return t_ok;
    }
};

}  // namespace

void axis_ranges(const LimitConstants &c, const double q[6], stewart_axis_ranges &out) {
    stewart_limits_output here;
    double here_inverse_norm = HUGE_VAL;
    check_limits(c, q, here, true, &here_inverse_norm);
    // Within the stroke L_k <= stroke_max, and |p + t e + R b_k - a_k| >= t - L_k: beyond twice
    // the shortest stroke_max, some leg is surely too long.
    const double reach =
        2.0 * *std::min_element(c.stroke_max, c.stroke_max + STEWART_LEGS) + 2.0 * kSmallestStep;
    // The platform's size: its radius, or its shortest leg if that is longer.
    const double size = std::max(c.geometry.characteristic_length, c.shortest_stroke_min);
    for (int axis = 0; axis < 6; ++axis)
        for (int side = 0; side < 2; ++side) {
            const double sign = side == 0 ? -1.0 : 1.0;
            double t = 0.0;
            stewart_limits_output beyond = here;
            if (within(here)) {
                const bool rotation = axis >= 3;
                Search s{c, {}, axis, sign, rotation ? M_PI : reach,
                         rotation ? std::max(c.longest_arm, 1e-12) : 1.0,
                         kConditionStep * (rotation ? 1.0 : size)};
                std::copy(q, q + 6, s.q);
                t = s.run(here, here_inverse_norm, beyond);
            }
            const int i = beyond.first - 1;
            const double end = q[axis] + sign * t;
            (side == 0 ? out.min : out.max)[axis] = end;
            (side == 0 ? out.min_limit : out.max_limit)[axis] = beyond.first;
            (side == 0 ? out.min_leg : out.max_leg)[axis] = i >= 0 ? beyond.leg[i] : 0;
            (side == 0 ? out.min_other_leg : out.max_other_leg)[axis] = i >= 0 ? beyond.other_leg[i] : 0;
        }
}

}  // namespace stewart
