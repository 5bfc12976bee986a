#include "forward/leg_factors.hpp"

#include <algorithm>
#include <cmath>

#include "kinematics/lu6.hpp"
#include "kinematics/motion.hpp"
#include "forward/leg_pairs.hpp"

namespace stewart {

void evaluate_legs(const PlatformGeometry &g, const double q[6], const double target[6],
                   LegsAt &c) {
    for (int i = 0; i < 6; i += 2) store_pair(c.q + i, load_pair(q + i));
    c.valid = true;
    // Kept: the step, the rates and the chord of the next solve need them again.
    ::sincos(q[3], &c.sin_roll, &c.cos_roll);  // (libm's sin and cos, one call)
    ::sincos(q[4], &c.sin_pitch, &c.cos_pitch);
    ::sincos(q[5], &c.sin_yaw, &c.cos_yaw);
    c.rotation =
        rotation_from_trig(c.cos_roll, c.sin_roll, c.cos_pitch, c.sin_pitch, c.cos_yaw, c.sin_yaw);
    const Eigen::Matrix3d &R = c.rotation;
    const double r00 = R(0, 0), r01 = R(0, 1), r02 = R(0, 2), r10 = R(1, 0), r11 = R(1, 1),
                 r12 = R(1, 2), r20 = R(2, 0), r21 = R(2, 1), r22 = R(2, 2);
    const double *platform = g.platform_points.data(), *base = g.base_points.data();
    for (int k = 0; k < STEWART_LEGS; k += 2) {  // legs k and k + 1
        const Pair b0 = point_pair(platform, 0, k), b1 = point_pair(platform, 1, k),
                   b2 = point_pair(platform, 2, k);
        const Pair a0 = r00 * b0 + r01 * b1 + r02 * b2, a1 = r10 * b0 + r11 * b1 + r12 * b2,
                   a2 = r20 * b0 + r21 * b1 + r22 * b2;
        store_pair(&c.arm[0][k], a0), store_pair(&c.arm[1][k], a1), store_pair(&c.arm[2][k], a2);
        const Pair d0 = q[0] + a0 - point_pair(base, 0, k);
        const Pair d1 = q[1] + a1 - point_pair(base, 1, k);
        const Pair d2 = q[2] + a2 - point_pair(base, 2, k);
        const Pair length = sqrt_pair(d0 * d0 + d1 * d1 + d2 * d2);
        store_pair(&c.length[k], length);
        store_pair(&c.axis[0][k], d0 / length), store_pair(&c.axis[1][k], d1 / length);
        store_pair(&c.axis[2][k], d2 / length);
        store_pair(&c.residual[k], length - load_pair(target + k));
    }
}

bool factor_legs(const PlatformGeometry &g, const LegsAt &at, LegFactors &f, double &norm1) {
    const double inv_scale = 1.0 / g.characteristic_length;
    for (int k = 0; k < STEWART_LEGS; k += 2) {  // legs k and k + 1: their rows
        const Pair n0 = load_pair(&at.axis[0][k]), n1 = load_pair(&at.axis[1][k]),
                   n2 = load_pair(&at.axis[2][k]);
        const Pair r0 = load_pair(&at.arm[0][k]), r1 = load_pair(&at.arm[1][k]),
                   r2 = load_pair(&at.arm[2][k]);
        const Pair row[6] = {n0,
                             n1,
                             n2,
                             (r1 * n2 - r2 * n1) * inv_scale,
                             (r2 * n0 - r0 * n2) * inv_scale,
                             (r0 * n1 - r1 * n0) * inv_scale};
#pragma GCC unroll 6
        for (int i = 0; i < 6; ++i) f.lu[6 * k + i] = row[i][0], f.lu[6 * k + 6 + i] = row[i][1];
    }
    // The column sums row after row (the scalar loop's order), three column pairs at a time.
    Pair column_sum[3] = {}, largest_pair[3] = {};
#pragma GCC unroll 6
    for (int k = 0; k < STEWART_LEGS; ++k)
#pragma GCC unroll 3
        for (int h = 0; h < 3; ++h) {
            const Pair magnitude = abs_pair(load_pair(f.lu + 6 * k + 2 * h));
            column_sum[h] += magnitude;
            largest_pair[h] = magnitude > largest_pair[h] ? magnitude : largest_pair[h];  // (exact)
        }
    // A sum of entries of at most 1 in size is finite unless an entry is not.
    const Pair total = column_sum[0] + column_sum[1] + column_sum[2];
    const bool finite = std::isfinite(total[0] + total[1]);
    norm1 = 0;
    double largest = 0;
    for (int h = 0; h < 3; ++h)
        for (int lane = 0; lane < 2; ++lane) {
            norm1 = std::max(norm1, column_sum[h][lane]);
            largest = std::max(largest, largest_pair[h][lane]);
        }
    f.trig = {at.cos_pitch, at.sin_pitch, at.cos_yaw, at.sin_yaw};
    f.scale = g.characteristic_length;
    return finite && lu6_factor(f.lu, f.pivot, f.order, largest);
}

bool pose_rates_from(const LegFactors &f, const PitchYawTrig &at, const double v[6],
                     double out[6]) {
    double w[6];
    lu6_solve(f.lu, f.order, v, w);
    out[0] = w[0], out[1] = w[1], out[2] = w[2];
    if (!(std::fabs(at.cos_pitch) > 1e-12)) return false;
    const double wx = w[3] / f.scale, wy = w[4] / f.scale, wz = w[5] / f.scale;
    out[3] = (at.cos_yaw * wx + at.sin_yaw * wy) / at.cos_pitch;
    out[4] = -at.sin_yaw * wx + at.cos_yaw * wy;
    out[5] = wz + at.sin_pitch * out[3];
    return true;
}

double inverse_norm1(const LegFactors &f) {
    // The columns of J^-1 = U^-1 L^-1 P are those of U^-1 L^-1 reordered, and the largest sum
    // does not see the order: solve for the six unit vectors at once, X = U^-1 L^-1 I, a row of X
    // in three two-double vectors (SSE2 on x86-64, NEON on ARM, plain doubles elsewhere). Each
    // column's arithmetic is that of its own substitution: the zeros above its unit entry stay
    // exact zeros, so the terms they subtract leave the other entries unchanged (bit for bit).
    typedef double Pair __attribute__((vector_size(16)));
    typedef long long Bits __attribute__((vector_size(16)));
    const Bits magnitude = {0x7fffffffffffffffLL, 0x7fffffffffffffffLL};  // |v|: sign bit cleared
    const double *a = f.lu;
    Pair x[6][3];
#pragma GCC unroll 6
    for (int i = 0; i < 6; ++i)
#pragma GCC unroll 3
        for (int h = 0; h < 3; ++h)
            x[i][h] = Pair{2 * h == i ? 1.0 : 0.0, 2 * h + 1 == i ? 1.0 : 0.0};
#pragma GCC unroll 6
    for (int k = 0; k < 6; ++k)
#pragma GCC unroll 6
        for (int i = k + 1; i < 6; ++i)
#pragma GCC unroll 3
            for (int h = 0; 2 * h <= k; ++h)  // (above row 2h, pair h holds zeros)
                x[i][h] -= a[6 * i + k] * x[k][h];
    Pair sum[3] = {};
#pragma GCC unroll 6
    for (int k = 5; k >= 0; --k) {
#pragma GCC unroll 6
        for (int c = k + 1; c < 6; ++c)
#pragma GCC unroll 3
            for (int h = 0; h < 3; ++h) x[k][h] -= a[6 * k + c] * x[c][h];
#pragma GCC unroll 3
        for (int h = 0; h < 3; ++h) {
            x[k][h] /= a[7 * k];
            sum[h] += reinterpret_cast<Pair>(reinterpret_cast<Bits>(x[k][h]) & magnitude);
        }
    }
    double largest = 0;
    for (int h = 0; h < 3; ++h) largest = std::max(largest, std::max(sum[h][0], sum[h][1]));
    return largest;
}

int determinant_sign(const LegFactors &f) { return lu6_determinant_sign(f.lu, f.pivot); }

bool factors_usable(LegFactors &f) {
    for (int i = 0; i < 36; ++i)
        if (!std::isfinite(f.lu[i])) return false;
    for (int i = 0; i < 6; ++i) f.order[i] = i;
    for (int k = 0; k < 6; ++k) {
        if (f.pivot[k] < k || f.pivot[k] > 5 || !(f.lu[7 * k] != 0)) return false;
        std::swap(f.order[k], f.order[f.pivot[k]]);
    }
    const double trig[5] = {f.trig.cos_pitch, f.trig.sin_pitch, f.trig.cos_yaw, f.trig.sin_yaw,
                            f.scale};
    for (double t : trig)
        if (!std::isfinite(t)) return false;
    return f.scale > 0;
}

}  // namespace stewart
