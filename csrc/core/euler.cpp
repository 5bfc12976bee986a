#include "core/euler.hpp"

#include <cmath>

namespace mbs {

Vec4 euler_parameters(const Mat3 &R) {
    // Pick the largest of 4 e0^2, 4 e1^2, ... to divide by: never close to zero.
    const double tr = R.trace();
    const double d[4] = {tr, R(0, 0), R(1, 1), R(2, 2)};
    int k = 0;
    for (int i = 1; i < 4; ++i)
        if (d[i] > d[k]) k = i;
    Vec4 p;
    if (k == 0) {
        const double s = 2.0 * std::sqrt(1.0 + tr);
        p << s / 4, (R(2, 1) - R(1, 2)) / s, (R(0, 2) - R(2, 0)) / s, (R(1, 0) - R(0, 1)) / s;
    } else if (k == 1) {
        const double s = 2.0 * std::sqrt(1.0 + 2 * R(0, 0) - tr);
        p << (R(2, 1) - R(1, 2)) / s, s / 4, (R(0, 1) + R(1, 0)) / s, (R(0, 2) + R(2, 0)) / s;
    } else if (k == 2) {
        const double s = 2.0 * std::sqrt(1.0 + 2 * R(1, 1) - tr);
        p << (R(0, 2) - R(2, 0)) / s, (R(0, 1) + R(1, 0)) / s, s / 4, (R(1, 2) + R(2, 1)) / s;
    } else {
        const double s = 2.0 * std::sqrt(1.0 + 2 * R(2, 2) - tr);
        p << (R(1, 0) - R(0, 1)) / s, (R(0, 2) + R(2, 0)) / s, (R(1, 2) + R(2, 1)) / s, s / 4;
    }
    if (p[0] < 0) p = -p;
    return p / p.norm();
}

}  // namespace mbs
