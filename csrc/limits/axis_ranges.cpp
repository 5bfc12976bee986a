#include "limits/axis_ranges.hpp"

#include <algorithm>
#include <cmath>

#include "limits/axis_motion.hpp"
#include "limits/range_bounds.hpp"

namespace stewart {

namespace {

// A stroke end is a closed-form root: the range ends this much inside it, well above the root's
// rounding (about 1e-8 even where a leg's length barely changes there) [m or rad].
constexpr double kInsideRoot = 1e-7;
// Bounds on the evaluations of one side: a march that has not met a limit by then ends at its
// last proven pose, reported with the class that held its last step (the condition's proof is
// loose near a singularity: docs/limits.md 7.2); the bisection only runs where a step proven
// safe met a limit after all (rounding at a margin of zero).
constexpr int kMaxSteps = 4000, kMaxBisection = 60;

bool within(const stewart_limits_output &o) { return o.failed == 0; }

// One pose along the search: the check's report and the legs. A class not checked there (known
// within its limit) has margin +inf.
struct Point {
    stewart_limits_output check;
    LegState legs;
};

// At tool pose q: the legs; with full_check the check of classes 1 to 4 (a proven step needs
// none: its classes are within); with_condition the condition number and the Jacobian it came
// from. Each as check_limits computes it.
void evaluate(const LimitConstants &c, const double q[6], bool full_check, bool with_condition,
              Point &p, LegJacobian &jacobian) {
    double platform[6];
    if (c.frames.identity) std::copy(q, q + 6, platform);
    else platform_pose(c.frames, q, nullptr, platform, nullptr);  // cannot fail without rates
    if (full_check) {
        check_platform_limits(c, platform, p.check, false);
        const int axis = STEWART_LIMIT_AXIS - 1;
        p.check.margin[axis] = axis_limit_margin(c, q, &p.check.leg[axis]);
    } else {
        for (int i = 0; i < STEWART_LIMIT_CLASSES; ++i) {
            p.check.margin[i] = HUGE_VAL;
            p.check.leg[i] = p.check.other_leg[i] = 0;
        }
        p.check.condition = 0.0;
    }
    leg_state(c, platform, p.legs);
    if (with_condition) {
        double inverse_condition = 0.0;
        p.check.condition = HUGE_VAL;
        jacobian.condition = HUGE_VAL;
        if (p.legs.has_direction) {
            leg_jacobian(c.geometry, p.legs.kinematics, jacobian);
            p.check.condition = jacobian.condition;
            if (std::isfinite(jacobian.condition) && jacobian.condition > 0.0)
                inverse_condition = 1.0 / jacobian.condition;
        }
        p.check.margin[STEWART_LIMIT_CONDITION - 1] = inverse_condition - 1.0 / c.warn_condition;
    }
    classify_margins(c, p.check);
}

// One side of one axis: a march from the pose in steps that range_bounds proves safe, up to the
// first stroke end (a closed-form root).
struct Side {
    const LimitConstants &c;
    const double *q;
    const RangeConstants &rc;
    int axis;
    double sign;
    AxisMotion motion;
    double axis_room;   // the way to this side's software position limit
    double axis_limit;  // that limit (axis_min or axis_max), the pose at t = axis_room

    void at(double t, bool full_check, bool with_condition, Point &p, LegJacobian &jacobian) const {
        double moved[6];
        std::copy(q, q + 6, moved);
        moved[axis] = t >= axis_room ? axis_limit : moved[axis] + sign * t;
        evaluate(c, moved, full_check, with_condition, p, jacobian);
    }

    // t of the last pose known within every limit, and the first limit's report beyond it
    // (STEWART_LIMIT_NONE at the search's end). `axis_room`: the way to the axis' own software
    // limit, which ends the side exactly there (the other axes' limits do not change).
    double run(const Point &here, const LegJacobian &here_jacobian,
               const double here_pairs[kLegPairs], double extent, double axis_room,
               stewart_limits_output &beyond) const {
        int stroke_leg = 0;
        const bool axis_ends = axis_room < extent;
        const double stroke_end =
            first_stroke_end(c, here.legs, motion, std::min(extent, axis_room), stroke_leg);
        Point now = here, next;
        LegJacobian jacobian;
        double t = 0.0;
        LegRates rates;
        leg_rates(c, here.legs, motion, rates);
        double condition_until =
            std::min(condition_radius(c, here.legs, rates, here_jacobian, motion), rates.reach);
        PairBounds pairs;
        pair_bounds(c, here.legs, rates, motion, here_pairs, pairs);
        Holder holder, held;
        for (int n = 0; n < kMaxSteps; ++n) {
            // Interference is measured only for pairs that may limit the step.
            const double condition_left = condition_until - t;
            double others = joint_radius(c, rc, now.legs, rates, motion, holder);
            if (condition_left < others) {
                others = condition_left;
                holder = {STEWART_LIMIT_CONDITION, 0, 0};
            }
            others = std::min(others, rates.reach);
            const double h = std::min(others, interference_radius(c, now.legs, t,
                                                                  std::min(others, stroke_end - t),
                                                                  pairs, holder));
            if (t + std::max(h, kAxisRangeTolerance) >= stroke_end)
                return end_side(here, t, h, stroke_end, stroke_leg, axis_ends, beyond);
            // A class within a tolerance of its limit: one tolerance ahead is beyond it (the
            // end), or the class only grazed its limit (the march goes on from there).
            const bool grazing = h < 0.5 * kAxisRangeTolerance;
            const double x = t + (grazing ? kAxisRangeTolerance : h);
            const bool with_condition = grazing || h >= condition_left;
            at(x, grazing, with_condition, next, jacobian);
            if (!within(next.check)) {
                beyond = next.check;
                return grazing ? t : bisect(t, x, beyond);
            }
            if (grazing && crosses_singularity(now.legs, next.legs, jacobian)) {
                beyond = next.check;
                beyond.first = STEWART_LIMIT_CONDITION;
                beyond.leg[STEWART_LIMIT_CONDITION - 1] = 0;
                beyond.other_leg[STEWART_LIMIT_CONDITION - 1] = 0;
                return t;
            }
            t = x;
            now = next;
            held = holder;
            leg_rates(c, now.legs, motion, rates);
            // Past a grazing check, the condition's bound restarts from the Jacobian there.
            if (with_condition)
                condition_until =
                    t +
                    std::min(condition_radius(c, now.legs, rates, jacobian, motion), rates.reach);
        }
        // Out of steps: the proof reaches no further; the class that held the steps holds it.
        beyond = now.check;
        beyond.first = held.limit;
        if (held.limit != STEWART_LIMIT_NONE) {
            beyond.leg[held.limit - 1] = held.leg;
            beyond.other_leg[held.limit - 1] = held.other_leg;
        }
        return t;
    }

    // The end of a side at the first stroke end, the axis' own limit or the search's end
    // (`end`), from t with a proven step h: within every limit up to min(t + h, end). Where the
    // proof stops short of the end (by less than the tolerance), the end itself is checked.
    double end_side(const Point &here, double t, double h, double end, int stroke_leg,
                    bool axis_ends, stewart_limits_output &beyond) const {
        const double last = stroke_leg ? std::max(t, end - kInsideRoot) : end;
        if (t + h < last) {
            Point p;
            LegJacobian jacobian;
            at(last, true, true, p, jacobian);
            if (!within(p.check)) {
                beyond = p.check;
                return t;
            }
        }
        beyond = here.check;
        const int limit = stroke_leg  ? STEWART_LIMIT_STROKE
                          : axis_ends ? STEWART_LIMIT_AXIS
                                      : STEWART_LIMIT_NONE;
        beyond.first = limit;
        if (limit != STEWART_LIMIT_NONE) {
            beyond.leg[limit - 1] = limit == STEWART_LIMIT_AXIS ? axis + 1 : stroke_leg;
            beyond.other_leg[limit - 1] = 0;
        }
        return last;
    }

    // Whether the leg Jacobian's determinant changes sign from `from` to `to` (the Jacobian
    // there given): a singular pose lies between them, however narrow the excursion of the
    // condition number (the mirror assembly lies beyond it).
    bool crosses_singularity(const LegState &from, const LegState &to,
                             const LegJacobian &to_jacobian) const {
        if (!from.has_direction || !to.has_direction) return false;
        LegJacobian from_jacobian;
        leg_jacobian(c.geometry, from.kinematics, from_jacobian);
        const double before = from_jacobian.transposed.partialPivLu().determinant();
        const double after = to_jacobian.transposed.partialPivLu().determinant();
        return (before > 0.0 && after < 0.0) || (before < 0.0 && after > 0.0);
    }

    // Bisection on the full check between t_ok (within) and t_bad (beyond) to the tolerance;
    // only where rounding beat a proven step.
    double bisect(double t_ok, double t_bad, stewart_limits_output &bad) const {
        Point p;
        LegJacobian jacobian;
        for (int n = 0; n < kMaxBisection && t_bad - t_ok > kAxisRangeTolerance; ++n) {
            const double t = 0.5 * (t_ok + t_bad);
            at(t, true, true, p, jacobian);
            if (within(p.check)) {
                t_ok = t;
            } else {
                t_bad = t;
                bad = p.check;
            }
        }
        return t_ok;
    }
};

// The class, leg and other leg of a report's first failing class (0s for none).
void end_of(const stewart_limits_output &beyond, int &limit, int &leg, int &other) {
    const int i = beyond.first - 1;
    limit = beyond.first;
    leg = i >= 0 ? beyond.leg[i] : 0;
    other = i >= 0 ? beyond.other_leg[i] : 0;
}

}  // namespace

void axis_ranges(const LimitConstants &c, const double q[6], stewart_axis_ranges &out) {
    Point here;
    LegJacobian here_jacobian;
    evaluate(c, q, true, true, here, here_jacobian);
    const RangeConstants rc = range_constants(c);
    double here_pairs[kLegPairs];
    pair_margins(c, here.legs, here_pairs);
    // Within the stroke L_k <= stroke_max, and |p + t e + R b_k - a_k| >= t - L_k: beyond twice
    // the shortest stroke_max, some leg is surely too long.
    const double reach = 2.0 * *std::min_element(c.stroke_max, c.stroke_max + STEWART_LEGS) +
                         2.0 * kAxisRangeTolerance;
    for (int axis = 0; axis < 6; ++axis)
        for (int side = 0; side < 2; ++side) {
            const double sign = side == 0 ? -1.0 : 1.0;
            double t = 0.0;
            stewart_limits_output beyond = here.check;
            const double limit = side == 0 ? c.axis_min[axis] : c.axis_max[axis];
            const double room = sign * (limit - q[axis]);
            if (within(here.check)) {
                const Side s{c,    q,    rc, axis, sign, axis_motion(c.frames, q, axis, sign),
                             room, limit};
                t = s.run(here, here_jacobian, here_pairs, axis >= 3 ? M_PI : reach, room, beyond);
            }
            (side == 0 ? out.min : out.max)[axis] = t >= room ? limit : q[axis] + sign * t;
            end_of(beyond, (side == 0 ? out.min_limit : out.max_limit)[axis],
                   (side == 0 ? out.min_leg : out.max_leg)[axis],
                   (side == 0 ? out.min_other_leg : out.max_other_leg)[axis]);
        }
}

}  // namespace stewart
