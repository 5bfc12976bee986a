#include "forward/branch.hpp"

#include <cmath>

#include "forward/leg_pairs.hpp"
#include "kinematics/lu6.hpp"
#include "kinematics/motion.hpp"
#include "stewart/stewart_forward.h"
#include "util/message.hpp"

namespace stewart {

Matrix36 platform_points_world(const PlatformGeometry &g, const double q[6]) {
    Matrix36 points = rotation_from_rpy(q[3], q[4], q[5]) * g.platform_points;
    points.colwise() += Eigen::Vector3d(q[0], q[1], q[2]);
    return points;
}

int jacobian_sign(const Matrix6 &transposed) {
    double a[36];
    Eigen::Map<Eigen::Matrix<double, 6, 6, Eigen::RowMajor>> rows(a);
    rows = transposed;
    int pivot[6], order[6];
    return lu6_factor(a, pivot, order, lu6_largest(a)) ? lu6_determinant_sign(a, pivot)
                                                       : 0;  // det J^T = det J
}

BranchSides branch_sides(const PlatformGeometry &g, double home_height) {
    // Below this sine of its angle to the horizontal a leg at home is horizontal.
    constexpr double kHorizontal = 1e-3;
    BranchSides sides;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Eigen::Vector3d leg =
            (Eigen::Vector3d(0, 0, home_height) + g.platform_points.col(k) - g.base_points.col(k))
                .normalized();
        const Eigen::Vector3d side = leg.z() > kHorizontal ? Eigen::Vector3d::UnitZ()
                                     : leg.z() < -kHorizontal
                                         ? Eigen::Vector3d(-Eigen::Vector3d::UnitZ())
                                         : leg;
        sides.base.col(k) = side;
        sides.platform.col(k) = side;  // the platform frame is the world's at home
        sides.vertical[k] = side == Eigen::Vector3d::UnitZ()    ? 1
                            : side == -Eigen::Vector3d::UnitZ() ? -1
                                                                : 0;
    }
    sides.all_vertical = true;
    for (int k = 0; k < STEWART_LEGS; ++k) sides.all_vertical &= sides.vertical[k] != 0;
    return sides;
}

int assembly_branch(const PlatformGeometry &g, const BranchSides &sides, const Eigen::Matrix3d &R,
                    const LegVectors &points, int jacobian_sign, int working_sign) {
    int branch = R(2, 2) > 0 ? 0 : STEWART_BRANCH_FLIPPED;  // the platform's normal points up
    if (jacobian_sign != working_sign) branch |= STEWART_BRANCH_SINGULARITY;
    // (R s) . leg as s . (R^T leg): no 3 x 6 product. The sums in Eigen's order (left to right),
    // so the verdicts are those of the vector expressions.
    bool below_base = false, platform_cardan = false;
    const double *base = g.base_points.data();
    if (sides.all_vertical) {  // s = +-z: s . leg = +-leg_z, s . R^T leg = +-(R^T leg)_z
        PairBits below = {0, 0}, above = {0, 0};
        for (int k = 0; k < STEWART_LEGS; k += 2) {  // legs k and k + 1
            const Pair l0 = load_pair(points.c[0] + k) - point_pair(base, 0, k),
                       l1 = load_pair(points.c[1] + k) - point_pair(base, 1, k),
                       l2 = load_pair(points.c[2] + k) - point_pair(base, 2, k);
            const Pair t2 = R(0, 2) * l0 + R(1, 2) * l1 + R(2, 2) * l2;
            const Pair side = load_pair(sides.vertical + k);
            below |= ~(side * l2 > 0);
            above |= ~(side * t2 > 0);
        }
        below_base = any(below), platform_cardan = any(above);
    } else {
        for (int k = 0; k < STEWART_LEGS; ++k) {
            const double l0 = points.c[0][k] - base[3 * k], l1 = points.c[1][k] - base[3 * k + 1],
                         l2 = points.c[2][k] - base[3 * k + 2];
            const double *b = sides.base.col(k).data(), *s = sides.platform.col(k).data();
            const double t0 = R(0, 0) * l0 + R(1, 0) * l1 + R(2, 0) * l2;
            const double t1 = R(0, 1) * l0 + R(1, 1) * l1 + R(2, 1) * l2;
            const double t2 = R(0, 2) * l0 + R(1, 2) * l1 + R(2, 2) * l2;
            below_base |= !(l0 * b[0] + l1 * b[1] + l2 * b[2] > 0);
            platform_cardan |= !(s[0] * t0 + s[1] * t1 + s[2] * t2 > 0);
        }
    }
    if (below_base) branch |= STEWART_BRANCH_BELOW_BASE;
    if (platform_cardan) branch |= STEWART_BRANCH_PLATFORM_CARDAN;
    return branch;
}

namespace {
constexpr double kPairSlack = 1e-12;  // relative, a few roundings
}  // namespace

LengthPairBounds length_pair_bounds(const PlatformGeometry &g) {
    LengthPairBounds b;
    int p = 0;
    for (int i = 0; i < STEWART_LEGS; ++i)
        for (int j = i + 1; j < STEWART_LEGS; ++j, ++p) {
            const double base = (g.base_points.col(i) - g.base_points.col(j)).norm();
            const double platform = (g.platform_points.col(i) - g.platform_points.col(j)).norm();
            b.difference[p] = base + platform;
            b.sum[p] = std::fabs(base - platform);
            b.least_sum[p] = b.sum[p] * (1 - kPairSlack) - 1e-15;
            b.largest_difference[p] = b.difference[p] * (1 + kPairSlack) + 1e-15;
        }
    return b;
}

stewart_status check_length_pairs(const LengthPairBounds &bounds, const double length[STEWART_LEGS],
                                  char *msg, size_t size) {
    // The common case first: every pair inside its bounds, two pairs at a time (the last lane
    // repeats the last pair).
    static constexpr int first[15] = {0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 3, 3, 4};
    static constexpr int second[15] = {1, 2, 3, 4, 5, 2, 3, 4, 5, 3, 4, 5, 4, 5, 5};
    PairBits outside = {0, 0};
#pragma GCC unroll 8
    for (int p = 0; p < 16; p += 2) {
        const int q = p + 1 < 15 ? p + 1 : 14;
        const Pair L_i = {length[first[p]], length[first[q]]};
        const Pair L_j = {length[second[p]], length[second[q]]};
        const Pair least_sum = {bounds.least_sum[p], bounds.least_sum[q]};
        const Pair largest_difference = {bounds.largest_difference[p],
                                         bounds.largest_difference[q]};
        outside |= (L_i + L_j < least_sum) | (abs_pair(L_i - L_j) > largest_difference);
    }
    if (!any(outside)) return STEWART_OK;
    int violations[STEWART_LEGS] = {0};
    int first_i = -1, first_j = -1, p = 0;
    double first_bound = 0;
    for (int i = 0; i < STEWART_LEGS; ++i)
        for (int j = i + 1; j < STEWART_LEGS; ++j, ++p) {
            const double L_i = length[i], L_j = length[j];
            if (L_i + L_j < bounds.least_sum[p]) {
                return set_message(msg, size, STEWART_ERR_UNREACHABLE,
                                   "no pose has these lengths: legs %d and %d are too short "
                                   "together, L%d + L%d = %g m < %g m, the least their attachment "
                                   "points allow",
                                   i + 1, j + 1, i + 1, j + 1, L_i + L_j, bounds.sum[p]);
            }
            if (std::fabs(L_i - L_j) > bounds.largest_difference[p]) {
                ++violations[i];
                ++violations[j];
                if (first_i < 0) first_i = i, first_j = j, first_bound = bounds.difference[p];
            }
        }
    if (first_i < 0) return STEWART_OK;
    int blamed = 0;
    for (int k = 1; k < STEWART_LEGS; ++k)
        if (violations[k] > violations[blamed]) blamed = k;
    if (violations[blamed] >= 2)  // out of line with several legs: that leg is the odd one
        return set_message(msg, size, STEWART_ERR_UNREACHABLE,
                           "no pose has these lengths: leg %d (L%d = %g m) differs from %d other "
                           "legs by more than the geometry allows (e.g. |L%d - L%d| = %g m > %g m)",
                           blamed + 1, blamed + 1, length[blamed], violations[blamed], first_i + 1,
                           first_j + 1, std::fabs(length[first_i] - length[first_j]), first_bound);
    return set_message(msg, size, STEWART_ERR_UNREACHABLE,
                       "no pose has these lengths: legs %d and %d differ by |L%d - L%d| = %g m, "
                       "more than the %g m their attachment points allow",
                       first_i + 1, first_j + 1, first_i + 1, first_j + 1,
                       std::fabs(length[first_i] - length[first_j]), first_bound);
}

}  // namespace stewart
