#include "table/singular_geometry.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include <Eigen/Dense>

#include "kinematics/joints.hpp"
#include "util/message.hpp"

namespace stewart {

namespace {

// A side's joints spread less than this (relative to their distance from the origin, the scale of
// their rounding) across a line are on it: the leg Jacobian's rank is then below 6 at every pose.
constexpr double kOnLine = 1e-9;

// Six digits: a place for the reader, not a value to copy; tiny rounding residues print as 0.
std::string point_text(const Eigen::Vector3d &v, double scale) {
    char text[96];
    auto shown = [&](double x) { return std::fabs(x) <= 1e-12 * scale ? 0.0 : x; };
    std::snprintf(text, sizeof text, "(%.6g, %.6g, %.6g)", shown(v[0]), shown(v[1]), shown(v[2]));
    return text;
}

// The line's direction with its largest component positive: one answer for the message.
Eigen::Vector3d line_direction(const Eigen::Vector3d &u) {
    Eigen::Index largest = 0;
    u.cwiseAbs().maxCoeff(&largest);
    return u[largest] < 0 ? Eigen::Vector3d(-u) : u;
}

}  // namespace

// Whether the joints lie on one line is the rank of their spread about their centroid: its
// second singular value is their largest distance from the best line, to a factor sqrt(6).
stewart_status check_not_singular_everywhere(const stewart_params &p, char *msg, size_t size) {
    const JointGeometry g = joint_geometry(p);
    const bool joints = p.geometry == 1.0;
    for (int side = 0; side < 2; ++side) {
        const Matrix36 &points = side ? g.platform_points : g.base_points;
        const Eigen::Vector3d centre = points.rowwise().mean();
        const Matrix36 spread = points.colwise() - centre;
        const double scale = points.cwiseAbs().maxCoeff();
        const Eigen::JacobiSVD<Eigen::Matrix<double, 3, 6>> svd(spread, Eigen::ComputeFullU);
        const Eigen::Vector3d sigma = svd.singularValues();
        const char *name = side ? "platform" : "base";
        const char *fields =
            joints ? (side ? "platform_joint" : "base_joint")
                   : (side ? "platform_radius, platform_angle" : "base_radius, base_angle");
        const char *frame = side ? "platform frame" : "base frame";
        if (sigma[0] <= kOnLine * scale)
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "%s: the six %s joints are at one point, %s m (%s): the platform "
                               "turns freely about it at every pose (singular everywhere)",
                               fields, name, point_text(centre, scale).c_str(), frame);
        if (sigma[1] <= kOnLine * scale)
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "%s: the six %s joints lie on one line, through %s m along %s (%s): "
                               "the platform turns freely about it at every pose (singular "
                               "everywhere); no leg's length changes with that rotation",
                               fields, name, point_text(centre, scale).c_str(),
                               point_text(line_direction(svd.matrixU().col(0)), 1.0).c_str(),
                               frame);
    }
    return STEWART_OK;
}

}  // namespace stewart
