#include "platform/forward_branch.hpp"

#include <cmath>

#include "core/dense_lu.hpp"
#include "platform/rigid_motion.hpp"
#include "stewart/stewart_forward.h"
#include "util/message.hpp"

namespace stewart {

namespace {

Matrix36 platform_points_world(const PlatformGeometry &g, const double q[6]) {
    Matrix36 points = rotation_from_rpy(q[3], q[4], q[5]) * g.platform_points;
    points.colwise() += Eigen::Vector3d(q[0], q[1], q[2]);
    return points;
}

}  // namespace

int leg_jacobian_sign(const PlatformGeometry &g, const double q[6]) {
    const Matrix36 points = platform_points_world(g, q);
    double rows[STEWART_LEGS * 6];  // row k: (n_k, p_k x n_k), p_k the platform point
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Eigen::Vector3d n = (points.col(k) - g.base_points.col(k)).normalized();
        const Eigen::Vector3d m = points.col(k).cross(n);
        for (int i = 0; i < 3; ++i) rows[6 * k + i] = n[i], rows[6 * k + 3 + i] = m[i];
    }
    int pivot[STEWART_LEGS];
    if (!mbs::lu_factor(rows, STEWART_LEGS, 6, 6, pivot)) return 0;
    int sign = 1;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        if (pivot[k] != k) sign = -sign;
        if (rows[7 * k] < 0) sign = -sign;
    }
    return sign;
}

int assembly_branch(const PlatformGeometry &g, const double q[6], int working_sign) {
    const Eigen::Matrix3d R = rotation_from_rpy(q[3], q[4], q[5]);
    const Eigen::Vector3d normal = R.col(2);
    const Matrix36 points = platform_points_world(g, q);
    int branch = normal.z() > 0 ? 0 : STEWART_BRANCH_FLIPPED;
    if (leg_jacobian_sign(g, q) != working_sign) branch |= STEWART_BRANCH_SINGULARITY;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Eigen::Vector3d leg = points.col(k) - g.base_points.col(k);
        if (!(leg.z() > 0)) branch |= STEWART_BRANCH_BELOW_BASE;
        if (!(leg.dot(normal) > 0)) branch |= STEWART_BRANCH_PLATFORM_CARDAN;
    }
    return branch;
}

double largest_point_displacement(const PlatformGeometry &g, const double a[6], const double b[6]) {
    return (platform_points_world(g, a) - platform_points_world(g, b)).colwise().norm().maxCoeff();
}

stewart_status check_length_pairs(const PlatformGeometry &g, const double length[STEWART_LEGS],
                                  char *msg, size_t size) {
    int violations[STEWART_LEGS] = {0};
    int first_i = -1, first_j = -1;
    double first_bound = 0;
    for (int i = 0; i < STEWART_LEGS; ++i)
        for (int j = i + 1; j < STEWART_LEGS; ++j) {
            const double bound = (g.base_points.col(i) - g.base_points.col(j)).norm() +
                                 (g.platform_points.col(i) - g.platform_points.col(j)).norm();
            // A relative slack of a few roundings: lengths computed from a pose at the bound
            // itself must pass.
            if (std::fabs(length[i] - length[j]) > bound * (1 + 1e-12) + 1e-15) {
                ++violations[i];
                ++violations[j];
                if (first_i < 0) first_i = i, first_j = j, first_bound = bound;
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
                           first_j + 1, std::fabs(length[first_i] - length[first_j]),
                           first_bound);
    return set_message(msg, size, STEWART_ERR_UNREACHABLE,
                       "no pose has these lengths: legs %d and %d differ by |L%d - L%d| = %g m, "
                       "more than the %g m their attachment points allow",
                       first_i + 1, first_j + 1, first_i + 1, first_j + 1,
                       std::fabs(length[first_i] - length[first_j]), first_bound);
}

}  // namespace stewart
