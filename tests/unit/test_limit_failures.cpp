// White-box test of the plant's limit verdicts (stewart::platform_limit_failures,
// csrc/limits/limit_check.cpp) against the full check they shortcut (check_platform_limits
// without the condition): the same joint and interference bits on random poses far from the
// limits and on poses put on the very edge of one (the limit or the leg diameter set to the
// pose's own widest angle or closest distance, a few ulps either way), one limit for all legs
// and one per leg; and the plant's verdicts at a quaternion's rotation (platform_limit_failures
// with a rotation) against the full check at that rotation's roll, pitch, yaw: the same verdicts
// from 1e-12 (rad, m) of a limit on, where only rounding tells them apart.
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "kinematics/closed_form.hpp"
#include "limits/limit_check.hpp"
#include "stewart/stewart.h"
#include "unity.h"

namespace {

// The fixture (setUp): the thesis platform's parameters, geometry and limit constants; a test may
// change params, which the next test's setUp puts back.
stewart_params params;
stewart::PlatformGeometry g;
stewart::LimitConstants thesis_limits;

double uniform(uint64_t &state, double a, double b) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return a + (b - a) * static_cast<double>(state >> 11) / 9007199254740992.0;
}

constexpr int kVerdictBits = 1 << (STEWART_LIMIT_BASE_JOINT - 1) |
                             1 << (STEWART_LIMIT_PLATFORM_JOINT - 1) |
                             1 << (STEWART_LIMIT_INTERFERENCE - 1);

// The full check's verdict bits at q.
int full_verdict(const stewart::LimitConstants &c, const double q[6]) {
    stewart_limits_output out;
    stewart::check_platform_limits(c, q, out, false);
    return out.failed & kVerdictBits;
}

// A random pose about home: small (far from the limits) or wide (beyond them).
void random_pose(uint64_t &rng, double home_height, double reach, double q[6]) {
    for (int i = 0; i < 3; ++i) q[i] = uniform(rng, -reach, reach);
    q[2] += home_height;
    for (int i = 3; i < 6; ++i) q[i] = uniform(rng, -2.5 * reach, 2.5 * reach);
}

// Constants with one joint limit per leg (the base's if base, else the platform's).
stewart::LimitConstants per_leg_limits(const stewart_params &params,
                                       const stewart::PlatformGeometry &g, bool base,
                                       const double limit[STEWART_LEGS]) {
    stewart::LimitConstants c = stewart::limit_constants(params, g, HUGE_VAL);
    for (int k = 0; k < STEWART_LEGS; ++k) {
        stewart_params one = params;
        (base ? one.base_joint_limit : one.platform_joint_limit) = limit[k];
        const stewart::LimitConstants ck = stewart::limit_constants(one, g, HUGE_VAL);
        if (base) {
            c.base_joint_limit[k] = limit[k];
            c.base_inside_cosine[k] = ck.base_inside_cosine[k];
        } else {
            c.platform_joint_limit[k] = limit[k];
            c.platform_inside_cosine[k] = ck.platform_inside_cosine[k];
        }
    }
    (base ? c.uniform_base_limit : c.uniform_platform_limit) = false;
    return c;
}

// The verdicts at 40,000 poses (make_pose(n, q, R): q the pose, R its rotation where the verdict
// wants one; odd n far from the limits, even n beyond them) by verdict(q, R) against the full
// check's at q: all equal, and more than 1,000 failing (the wide poses do reach the limits).
template <class MakePose, class Verdict>
void require_full_verdicts(const stewart::LimitConstants &c, MakePose make_pose, Verdict verdict) {
    int differing = 0, failing = 0;
    for (int n = 0; n < 40000; ++n) {
        double q[6];
        Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
        make_pose(n, q, R);
        const int expected = full_verdict(c, q);
        failing += expected != 0;
        differing += verdict(q, R) != expected;
    }
    TEST_ASSERT_EQUAL_INT(0, differing);
    TEST_ASSERT_TRUE(failing > 1000);
}

void test_far_and_beyond(void) {
    uint64_t rng = 2026;
    require_full_verdicts(
        thesis_limits,
        [&](int n, double q[6], Eigen::Matrix3d &) {
            random_pose(rng, params.home_height, n % 2 ? 0.05 : 0.4, q);
        },
        [&](const double q[6], const Eigen::Matrix3d &) {
            return stewart::platform_limit_failures(thesis_limits, q);
        });
}

// Every pose on the edge: a limit or the diameter moved onto the pose's own value, then a few
// ulps either way, so that the verdict turns on the last bits; and the joint limits a little wider,
// across the cosine pre-test's slack.
void test_on_the_edge(void) {
    uint64_t rng = 99;
    int differing = 0, failing = 0, uniform_checks = 0;
    // the angle limits also a little wider, about where the cosine pre-test's slack ends
    const double offsets[] = {0.0, 1e-11, 1e-10, 5e-10, 1e-9, 2e-9, 1e-8};
    for (int n = 0; n < 1500; ++n) {
        double q[6];
        random_pose(rng, params.home_height, 0.15, q);
        stewart_params wide = params;  // nothing fails: the margins are the values themselves
        wide.base_joint_limit = wide.platform_joint_limit = M_PI;
        wide.leg_diameter = 0.0;
        stewart_limits_output out;
        stewart::check_platform_limits(stewart::limit_constants(wide, g, HUGE_VAL), q, out, false);
        const double base_angle = M_PI - out.margin[STEWART_LIMIT_BASE_JOINT - 1];
        const double platform_angle = M_PI - out.margin[STEWART_LIMIT_PLATFORM_JOINT - 1];
        const double distance = out.margin[STEWART_LIMIT_INTERFERENCE - 1];
        for (int step = 0; step < 7 * 7; ++step) {
            const int ulps = step % 7 - 3;
            const double offset = offsets[step / 7];
            stewart_params edge = params;
            edge.base_joint_limit = base_angle + offset;
            edge.platform_joint_limit = platform_angle + offset;
            edge.leg_diameter = distance;
            double *values[3] = {&edge.base_joint_limit, &edge.platform_joint_limit,
                                 &edge.leg_diameter};
            for (double *v : values)
                for (int u = 0; u < std::abs(ulps); ++u)
                    *v = std::nextafter(*v, ulps > 0 ? HUGE_VAL : 0.0);
            const stewart::LimitConstants c = stewart::limit_constants(edge, g, HUGE_VAL);
            const int expected = full_verdict(c, q);
            failing += expected != 0;
            differing += stewart::platform_limit_failures(c, q) != expected;
            ++uniform_checks;
            // one limit per leg: the edge on a random leg, the others wide or narrow
            for (int base = 0; base < 2; ++base) {
                double limit[STEWART_LEGS];
                for (double &l : limit) l = uniform(rng, 0.0, 1.0) < 0.8 ? 1.2 : 0.1;
                limit[static_cast<int>(uniform(rng, 0, STEWART_LEGS))] =
                    base ? edge.base_joint_limit : edge.platform_joint_limit;
                const stewart::LimitConstants cl = per_leg_limits(edge, g, base, limit);
                const int e = full_verdict(cl, q);
                differing += stewart::platform_limit_failures(cl, q) != e;
            }
        }
    }
    TEST_ASSERT_EQUAL_INT(0, differing);
    TEST_ASSERT_TRUE(failing > uniform_checks / 4);  // the edges do fail on one side
}

// Limits at the ends of their range: 0 fails at any angle but zero, pi never fails.
void test_extreme_limits(void) {
    uint64_t rng = 7;
    int differing = 0;
    const double limits[] = {0.0, 1e-12, M_PI - 1e-12, M_PI};
    for (double limit : limits) {
        stewart_params p = params;
        p.base_joint_limit = p.platform_joint_limit = limit;
        const stewart::LimitConstants c = stewart::limit_constants(p, g, HUGE_VAL);
        for (int n = 0; n < 2000; ++n) {
            double q[6];
            random_pose(rng, params.home_height, 0.3, q);
            differing += stewart::platform_limit_failures(c, q) != full_verdict(c, q);
        }
    }
    TEST_ASSERT_EQUAL_INT(0, differing);
}

// A random rotation (a normalised random quaternion, as the plant's state gives it) and its
// principal roll, pitch, yaw (as the plant's angles_of_rotation on the principal branch).
Eigen::Matrix3d random_rotation(uint64_t &rng, double spread, double angles[3]) {
    Eigen::Quaterniond q(1.0, uniform(rng, -spread, spread), uniform(rng, -spread, spread),
                         uniform(rng, -spread, spread));
    q.normalize();
    const Eigen::Matrix3d R = q.toRotationMatrix();
    angles[0] = std::atan2(R(2, 1), R(2, 2));
    angles[1] = std::asin(std::fmax(-1.0, std::fmin(1.0, -R(2, 0))));
    angles[2] = std::atan2(R(1, 0), R(0, 0));
    return R;
}

// The verdicts at a rotation against the full check at its angles: on poses far from and beyond
// the limits, equal; with a limit and the diameter moved onto the pose's own widest angle and
// closest distance and then `offset` either way, equal from |offset| >= 1e-12 on (the rotations
// differ by a few roundings, 1e-16, the angles and distances by as little).
void test_rotation_verdicts(void) {
    uint64_t rng = 4242;
    require_full_verdicts(
        thesis_limits,
        [&](int n, double q[6], Eigen::Matrix3d &R) {
            R = random_rotation(rng, n % 2 ? 0.05 : 0.5, q + 3);
            for (int i = 0; i < 3; ++i) q[i] = uniform(rng, -0.3, 0.3);
            q[2] += params.home_height;
        },
        [&](const double q[6], const Eigen::Matrix3d &R) {
            return stewart::platform_limit_failures(thesis_limits,
                                                    Eigen::Vector3d(q[0], q[1], q[2]), R);
        });
    int differing = 0;
    const double offsets[] = {-1e-9, -1e-11, -1e-12, 0.0, 1e-12, 1e-11, 1e-9};
    int at_rounding = 0, checks = 0;
    for (int n = 0; n < 2000; ++n) {
        double q[6];
        const Eigen::Matrix3d R = random_rotation(rng, 0.15, q + 3);
        for (int i = 0; i < 3; ++i) q[i] = uniform(rng, -0.15, 0.15);
        q[2] += params.home_height;
        stewart_params wide = params;
        wide.base_joint_limit = wide.platform_joint_limit = M_PI;
        wide.leg_diameter = 0.0;
        stewart_limits_output out;
        stewart::check_platform_limits(stewart::limit_constants(wide, g, HUGE_VAL), q, out, false);
        for (double offset : offsets) {
            for (int which = 0; which < 3; ++which) {  // the base's, the platform's, the diameter
                stewart_params edge = params;
                edge.base_joint_limit = edge.platform_joint_limit = M_PI / 2;
                edge.leg_diameter = 0.0;
                const int index = (which == 0   ? STEWART_LIMIT_BASE_JOINT
                                   : which == 1 ? STEWART_LIMIT_PLATFORM_JOINT
                                                : STEWART_LIMIT_INTERFERENCE) -
                                  1;
                const double value = which < 2 ? M_PI - out.margin[index] : out.margin[index];
                (which == 0   ? edge.base_joint_limit
                 : which == 1 ? edge.platform_joint_limit
                              : edge.leg_diameter) = value + offset;
                const stewart::LimitConstants ce = stewart::limit_constants(edge, g, HUGE_VAL);
                const bool same =
                    stewart::platform_limit_failures(ce, Eigen::Vector3d(q[0], q[1], q[2]), R) ==
                    full_verdict(ce, q);
                ++checks;
                if (offset == 0.0) at_rounding += !same;
                else differing += !same;
            }
        }
    }
    std::printf("%d of %d verdicts on the very edge differ at rounding distance\n", at_rounding,
                checks / 7);
    TEST_ASSERT_EQUAL_INT(0, differing);
}

// The verdicts with a clearance kept from pose to pose (the plant's, platform_limit_failures with
// a LimitClearance) against the exact ones, along random walks that wander in and out of the
// limits: steps of 1e-4 to 3e-2 (m, rad), poses up to 0.4 m and rad from home, with the default
// limits and with narrow ones (joints at 0.3 rad, a leg diameter of 0.25 m, so that walks spend
// long stretches on the edges). Equal everywhere; the clearance spares the check on most poses.
void test_clearance(void) {
    stewart_params narrow = params;
    narrow.base_joint_limit = narrow.platform_joint_limit = 0.3;
    narrow.leg_diameter = 0.25;
    // actuators: a body and a rod, each thick enough to meet its neighbours' parts
    stewart_params shaped = narrow;
    shaped.leg_body_diameter = 0.2, shaped.leg_body_length = 0.3;
    shaped.leg_rod_diameter = 0.15, shaped.leg_rod_length = 0.35;
    uint64_t rng = 5150;
    int differing = 0, failing = 0, spared = 0, poses = 0;
    for (const stewart_params &limits : {params, narrow, shaped}) {
        const stewart::LimitConstants c = stewart::limit_constants(limits, g, HUGE_VAL);
        for (int walk = 0; walk < 60; ++walk) {
            const double step = std::pow(10.0, uniform(rng, -4, -1.5));
            Eigen::Vector3d position(0, 0, params.home_height);
            Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
            stewart::LimitClearance clearance;
            for (int n = 0; n < 1000; ++n, ++poses) {
                const Eigen::Vector3d home(0, 0, params.home_height);
                for (int i = 0; i < 3; ++i)
                    position[i] += step * uniform(rng, -1, 1) - 0.01 * (position[i] - home[i]);
                const Eigen::Vector3d axis(uniform(rng, -1, 1), uniform(rng, -1, 1),
                                           uniform(rng, -1, 1));
                const Eigen::AngleAxisd back(q.conjugate());  // drift toward level
                q = Eigen::Quaterniond(Eigen::AngleAxisd(0.01 * back.angle(), back.axis())) * q;
                if (axis.norm() > 1e-3)
                    q = Eigen::Quaterniond(Eigen::AngleAxisd(step * uniform(rng, 0, 1.7),
                                                             axis.normalized())) *
                        q;
                q.normalize();
                const Eigen::Matrix3d R = q.toRotationMatrix();
                const Eigen::Vector3d before = clearance.position;
                const int kept = stewart::platform_limit_failures(c, position, R, clearance);
                const int exact = stewart::platform_limit_failures(c, position, R);
                differing += kept != exact;
                failing += exact != 0;
                spared += clearance.valid && clearance.position == before && before != position;
            }
        }
    }
    std::printf("clearance: %d of %d poses spared the check, %d failing, %d differing\n", spared,
                poses, failing, differing);
    TEST_ASSERT_EQUAL_INT(0, differing);
    TEST_ASSERT_TRUE(failing > poses / 20);  // the walks do reach the limits
    TEST_ASSERT_TRUE(spared > poses / 4);    // and the clearance spares many checks
}

// What the clearance's bound rests on (limit_check.cpp, platform_limit_failures with a
// LimitClearance), measured here from the geometry itself: from a pose to one moved by a random
// small motion (1e-5 to 1e-1 m and rad), with delta = |dp| + |dR|_F max_k |b_k|, every leg's
// length moves by at most delta, its base joint's cosine by at most 2 delta / |d_k| (the first
// pose's length), its platform joint's by that plus |dR|_F, and every pair's segment distance and
// sphere gap by at most 2 delta. The largest ratio of a move to its allowance, per quantity
// (lengths, base cosines, platform cosines, distances, sphere gaps), into worst.
void worst_bound_ratios(const stewart::LimitConstants &c, double home_height, uint64_t &rng,
                        double worst[5]) {
    const stewart::PlatformGeometry &g = c.geometry;
    for (int i = 0; i < 5; ++i) worst[i] = 0;
    for (int sample = 0; sample < 20000; ++sample) {
        Eigen::Vector3d p[2];
        Eigen::Matrix3d R[2];
        double q[6];
        R[0] = random_rotation(rng, 0.3, q);
        for (int i = 0; i < 3; ++i) p[0][i] = uniform(rng, -0.2, 0.2);
        p[0][2] += home_height;
        const double size = std::pow(10.0, uniform(rng, -5, -1));
        const Eigen::Vector3d axis(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
        if (!(axis.norm() > 1e-3)) continue;
        R[1] = Eigen::AngleAxisd(size * uniform(rng, 0, 1), axis.normalized()).toRotationMatrix() *
               R[0];
        for (int i = 0; i < 3; ++i) p[1][i] = p[0][i] + size * uniform(rng, -1, 1);
        const double turned = (R[1] - R[0]).norm();
        const double delta = (p[1] - p[0]).norm() + turned * c.platform_radius;
        Eigen::Vector3d top[2][STEWART_LEGS], n[2][STEWART_LEGS];
        double length[2][STEWART_LEGS];
        for (int s = 0; s < 2; ++s)
            for (int k = 0; k < STEWART_LEGS; ++k) {
                top[s][k] = p[s] + R[s] * g.platform_points.col(k);
                const Eigen::Vector3d d = top[s][k] - g.base_points.col(k);
                length[s][k] = d.norm();
                n[s][k] = d / length[s][k];
            }
        for (int k = 0; k < STEWART_LEGS; ++k) {
            const double turn_allowed = 2 * delta / length[0][k];
            const double base_move = std::fabs((n[1][k] - n[0][k]).dot(c.base_neutral.col(k)));
            const double platform_move = std::fabs(n[1][k].dot(R[1] * c.platform_neutral.col(k)) -
                                                   n[0][k].dot(R[0] * c.platform_neutral.col(k)));
            worst[0] = std::fmax(worst[0], std::fabs(length[1][k] - length[0][k]) / delta);
            worst[1] = std::fmax(worst[1], base_move / turn_allowed);
            worst[2] = std::fmax(worst[2], platform_move / (turn_allowed + turned));
        }
        for (int i = 0; i < STEWART_LEGS; ++i)
            for (int j = i + 1; j < STEWART_LEGS; ++j) {
                double distance[2], gap[2];
                for (int s = 0; s < 2; ++s) {
                    distance[s] =
                        std::sqrt(stewart::segment_distance_squared(g.base_points.col(i), top[s][i],
                                                                    g.base_points.col(j),
                                                                    top[s][j]));
                    const Eigen::Vector3d mi = 0.5 * (g.base_points.col(i) + top[s][i]),
                                          mj = 0.5 * (g.base_points.col(j) + top[s][j]);
                    gap[s] = (mi - mj).norm() - 0.5 * (length[s][i] + length[s][j]);
                }
                worst[3] = std::fmax(worst[3], std::fabs(distance[1] - distance[0]) / (2 * delta));
                worst[4] = std::fmax(worst[4], std::fabs(gap[1] - gap[0]) / (2 * delta));
            }
    }
}

void test_clearance_bound(void) {
    uint64_t rng = 8086;
    double worst[5];
    worst_bound_ratios(thesis_limits, params.home_height, rng, worst);
    std::printf("clearance bound: the largest moves of lengths, base and platform cosines, "
                "distances, sphere gaps are %.3g, %.3g, %.3g, %.3g, %.3g of their allowances\n",
                worst[0], worst[1], worst[2], worst[3], worst[4]);
    for (double w : worst) TEST_ASSERT_TRUE(w <= 1.0);
}

// The pose moved from (p, R) by s times a move: dp along the position, a turn of s * angle about
// axis (rotation pre-multiplied, as the plant's state turns).
void moved_pose(const Eigen::Vector3d &p, const Eigen::Matrix3d &R, const Eigen::Vector3d &dp,
                const Eigen::Vector3d &axis, double angle, double s, Eigen::Vector3d &p1,
                Eigen::Matrix3d &R1) {
    p1 = p + s * dp;
    R1 = Eigen::AngleAxisd(s * angle, axis).toRotationMatrix() * R;
}

// The skip decision (clearance_spares) at its edge: from random poses near the limits (the
// clearance of an exact check there), along random moves (translations, turns, both), the
// farthest pose the clearance still spares (bisection on the move's size), where the exact check
// must find nothing. How far the spared moves go into the clearance: the smallest share of the
// joint cosine's clearance left at such a pose, of the interference's (as recorded: a far pair's
// sphere gap, a lower bound that jumps where the pair is measured instead), and of the shortest
// leg's above min_length, into least_left. Seen to fail with the allowance (delta) divided by 10
// (112 failing in the first set), not by 5: the moves sampled stay within 1/5 of the bound.
int spared_failures(const stewart::LimitConstants &c, double home_height, uint64_t &rng,
                    int &spared, double least_left[3]) {
    int failures = 0;
    for (int sample = 0; sample < 6000; ++sample) {
        double q[6];
        random_pose(rng, home_height, 0.12, q);
        const Eigen::Vector3d p(q[0], q[1], q[2]);
        const Eigen::Matrix3d R = stewart::rotation_from_rpy(q[3], q[4], q[5]);
        stewart::LimitClearance clearance;
        if (stewart::platform_limit_failures(c, p, R, clearance) != 0 || !clearance.valid) continue;
        Eigen::Vector3d dp(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)),
            axis(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
        if (!(axis.norm() > 1e-3)) continue;
        axis.normalize();
        const int kind = sample % 3;  // translation, turn, both
        if (kind == 1) dp.setZero();
        const double angle = kind == 0 ? 0.0 : uniform(rng, 0.2, 1.0);
        double inside = 0, outside = 1;  // scales spared and not (a move of 1 m or rad is not)
        Eigen::Vector3d p1;
        Eigen::Matrix3d R1;
        for (int i = 0; i < 60; ++i) {
            const double mid = 0.5 * (inside + outside);
            moved_pose(p, R, dp, axis, angle, mid, p1, R1);
            (stewart::clearance_spares(c, clearance, p1, R1) ? inside : outside) = mid;
        }
        if (inside == 0) continue;
        moved_pose(p, R, dp, axis, angle, inside, p1, R1);
        if (!stewart::clearance_spares(c, clearance, p1, R1)) continue;
        ++spared;
        stewart::LimitClearance there;
        failures += stewart::platform_limit_failures(c, p1, R1, there) != 0;
        if (!there.valid) continue;
        least_left[0] = std::fmin(least_left[0], there.joint_cosine / clearance.joint_cosine);
        least_left[1] = std::fmin(least_left[1], there.interference / clearance.interference);
        least_left[2] =
            std::fmin(least_left[2], (there.shortest_leg - c.geometry.min_length) /
                                         (clearance.shortest_leg - c.geometry.min_length));
    }
    return failures;
}

void test_clearance_edge(void) {
    params.base_joint_limit = 0.35;
    params.platform_joint_limit = 0.4;
    params.leg_diameter = 0.1;
    // another 6-6 geometry: smaller platform, legs that cross (1 and 2, 3 and 4, 5 and 6)
    stewart_params crossing = params;
    crossing.platform_radius = 0.35;
    crossing.home_height = 0.6;
    const double angle[STEWART_LEGS] = {25, 5, 145, 125, 265, 245};  // [deg]
    for (int k = 0; k < STEWART_LEGS; ++k) crossing.platform_angle[k] = angle[k] * M_PI / 180;
    crossing.leg_diameter = 0.01;
    // actuators (the clearance's moves are twice those of plain legs: parts end at a + f d)
    stewart_params shaped = params;
    shaped.leg_body_diameter = 0.12, shaped.leg_body_length = 0.25;
    shaped.leg_rod_diameter = 0.08, shaped.leg_rod_length = 0.3;
    const double per_leg[STEWART_LEGS] = {0.3, 0.45, 0.35, 0.5, 0.25, 0.4};
    uint64_t rng = 6502;
    for (const stewart_params &set : {params, crossing, shaped}) {
        const stewart::PlatformGeometry g = stewart::platform_geometry(set);
        const stewart::LimitConstants constants[3] = {stewart::limit_constants(set, g, HUGE_VAL),
                                                      per_leg_limits(set, g, true, per_leg),
                                                      per_leg_limits(set, g, false, per_leg)};
        for (const stewart::LimitConstants &c : constants) {
            int spared = 0;
            double least_left[3] = {1, 1, 1};
            const int failures = spared_failures(c, set.home_height, rng, spared, least_left);
            std::printf("clearance edge: %d spared moves, %d failing; least clearance left of "
                        "the joint cosine %.3g, interference %.3g, leg length %.3g\n",
                        spared, failures, least_left[0], least_left[1], least_left[2]);
            TEST_ASSERT_EQUAL_INT(0, failures);
            TEST_ASSERT_TRUE(spared > 300);
            TEST_ASSERT_TRUE(least_left[0] < 0.9);  // the spared moves reach into the clearance
        }
    }
}

}  // namespace

void setUp(void) {
    stewart_params_default(&params);
    g = stewart::platform_geometry(params);
    thesis_limits = stewart::limit_constants(params, g, HUGE_VAL);
}

void tearDown(void) {}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_far_and_beyond);
    RUN_TEST(test_on_the_edge);
    RUN_TEST(test_extreme_limits);
    RUN_TEST(test_rotation_verdicts);
    RUN_TEST(test_clearance);
    RUN_TEST(test_clearance_bound);
    RUN_TEST(test_clearance_edge);
    return UNITY_END();
}
