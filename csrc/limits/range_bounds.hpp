// How far along an axis motion (limits/axis_motion.hpp) the joint-angle, interference and
// condition classes provably stay within their limits, from one pose: the steps of the axis
// ranges' march, none of which can step over an excursion beyond a limit (docs/limits.md 7.2).
// Every bound assumes that the legs stay within their strokes over the step (L_k >= stroke_min
// bounds how fast a leg turns): the march never steps past the first stroke end.
#pragma once

#include "limits/axis_motion.hpp"

namespace stewart {

// What the bounds need of the limits beyond LimitConstants, once per search.
struct RangeConstants {
    double cos_base_limit[STEWART_LEGS], cos_platform_limit[STEWART_LEGS];
    bool base_can_fail[STEWART_LEGS], platform_can_fail[STEWART_LEGS];  // limit below pi
};
RangeConstants range_constants(const LimitConstants &c);

// Per leg at one pose of the motion: the unit leg vector's rate u' = P d' / L (P = I - u u^T),
// the platform joint's speed bound v (|d'| <= v all along the motion), and bounds |u'| <= turn
// and |u''| <= bend over the next `reach` of the motion, from a lower bound on L_k there: the
// larger of stroke_min (all along the side) and half the leg's length now (up to where it can
// have halved: |L'| <= v).
struct LegRates {
    Matrix36 turn_rate;
    double speed[STEWART_LEGS], turn[STEWART_LEGS], bend[STEWART_LEGS];
    double reach;
};

// Which limit held a step of the march (the class, its leg and an interfering pair's other
// leg): what an end reports where the proof ran out of steps.
struct Holder {
    int limit = STEWART_LIMIT_NONE, leg = 0, other_leg = 0;
};
void leg_rates(const LimitConstants &c, const LegState &legs, const AxisMotion &m, LegRates &out);

// The largest h >= 0 with g + slope h - curvature h^2 / 2 >= 0 (g >= 0, curvature >= 0): how
// far a quantity at g with that slope, whose second derivative is at least -curvature, stays
// >= 0 (0 if g <= 0, +inf if it never falls).
double taylor_radius(double g, double slope, double curvature);

// Both joint-angle classes: cos(angle) - cos(limit) per joint, its slope along the motion and a
// bound on its second derivative (the leg's turn and, at the platform, the neutral axis' turn).
// A class whose limit is pi or more cannot fail.
double joint_radius(const LimitConstants &c, const RangeConstants &rc, const LegState &legs,
                    const LegRates &rates, const AxisMotion &m, Holder &holder);

// The interference class along one side, per pair of legs: the margin (distance - leg_diameter)
// last computed and the t it was computed at, and how fast that distance can change along the
// motion (constant along it: 1 per unit of a translation; for a turn the fastest relative speed
// of two points of the legs, max(v_i, v_j, |w x (top_i - top_j)|)).
constexpr int kLegPairs = 15;
struct PairBounds {
    double margin[kLegPairs], at[kLegPairs], rate[kLegPairs];
};
// Every pair's margin at `legs` (t = 0 of every side).
void pair_margins(const LimitConstants &c, const LegState &legs, double margin[kLegPairs]);
// The rates along m, with the margins at t = 0.
void pair_bounds(const LimitConstants &c, const LegState &legs, const LegRates &rates,
                 const AxisMotion &m, const double margin[kLegPairs], PairBounds &out);
// How far from t (legs: there) no pair can come within leg_diameter, or `cap` if at least that:
// a pair whose stored margin, less its rate times the way since, is that far from its limit
// needs no new distance; the others are measured here (and stored). +inf with no interference
// check (leg_diameter 0, or parts of no thickness).
double interference_radius(const LimitConstants &c, const LegState &legs, double t, double cap,
                           PairBounds &pairs, Holder &holder);

// The condition number: J^T(t + h) = J^T (I + X) with ||X|| <= h ||J^-T D|| + ||J^-T|| M h^2 / 2
// (D = dJ^T/dt here, M bounds |d2J^T/dt2| over the step), so that cond(t + h) <=
// (||J^T|| + h S) ||J^-T|| / (1 - ||X||) (S bounds |dJ^T/dt|) stays <= warn_condition up to the
// returned h (infinity norms, the check's). jacobian: the check's at `legs`.
double condition_radius(const LimitConstants &c, const LegState &legs, const LegRates &rates,
                        const LegJacobian &jacobian, const AxisMotion &m);

}  // namespace stewart
