// The inverse's drive columns: what each leg's motor must give for the motion and forces found.
#include "drives/drive_outputs.hpp"

#include <cmath>
#include <cstring>

#include "util/columns.hpp"
#include "util/message.hpp"

namespace stewart {

int legs_over(const double (&value)[STEWART_LEGS], const double (&limit)[STEWART_LEGS]) {
    int legs = 0;
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (limit[k] > 0 && std::fabs(value[k]) > limit[k]) legs |= 1 << k;
    return legs;
}

void fill_drive_outputs(const LegDrive (&drive)[STEWART_LEGS], const stewart_params &p,
                        stewart_inverse_output &out) {
    const stewart_lengths &l = out.lengths;
    int current_legs = 0, voltage_legs = 0, speed_legs = 0;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const LegDrive &d = drive[k];
        const double r = d.motor_per_leg;
        if (r == 0) {  // no drive: every column 0 (not r times a negative rate, -0)
            out.motor_angle[k] = out.motor_speed[k] = out.motor_accel[k] = 0;
            out.motor_torque[k] = out.current[k] = out.current_rate[k] = out.voltage[k] = 0;
            out.electrical_power[k] = out.motor_power[k] = 0;
            continue;
        }
        const double torque = drive_torque(d, out.force[k], l.length_rate[k], l.length_accel[k]);
        const double current = torque / d.torque_constant, speed = r * l.length_rate[k];
        const double voltage = d.resistance * current + d.torque_constant * speed;
        out.motor_angle[k] = r * l.length[k];
        out.motor_speed[k] = speed;
        out.motor_accel[k] = r * l.length_accel[k];
        out.motor_torque[k] = torque;
        out.current[k] = current;
        out.current_rate[k] = 0;
        out.voltage[k] = voltage;
        out.electrical_power[k] = voltage * current;
        out.motor_power[k] = torque * speed;
        // the limits (0: none) as legs_over takes them
        current_legs |= (p.current_max[k] > 0 && std::fabs(current) > p.current_max[k]) << k;
        voltage_legs |= (p.voltage_max[k] > 0 && std::fabs(voltage) > p.voltage_max[k]) << k;
        speed_legs |= (p.motor_speed_max[k] > 0 && std::fabs(speed) > p.motor_speed_max[k]) << k;
    }
    out.current_max_legs = current_legs;
    out.voltage_max_legs = voltage_legs;
    out.motor_speed_max_legs = speed_legs;
}

bool drive_outputs_finite(const stewart_inverse_output &o) {
    double sum = 0;  // inf or NaN in any term makes the sum's difference with itself NaN
    for (int k = 0; k < STEWART_LEGS; ++k)
        sum += ((o.motor_torque[k] + o.current[k]) + (o.voltage[k] + o.electrical_power[k])) +
               (o.motor_power[k] + o.motor_angle[k]);
    return sum - sum == 0;
}

#define PUT(name, member, count, type, unit, description) put_row(out.name, j, o.member);

void batch_drive_zeros(const stewart_inverse_batch_outputs &out, size_t first, size_t last) {
#define ZEROS(name, member, count, type, unit, description) \
    if (out.name)                                           \
        std::memset(out.name + first * (count), 0, (last - first) * (count) * sizeof(type));
    STEWART_INVERSE_DRIVE_OUTPUT_TABLE(ZEROS)
#undef ZEROS
}

bool batch_drive_row(const LegDrive (&drive)[STEWART_LEGS], const stewart_params &p,
                     const stewart_inverse_batch_outputs &out, size_t j) {
    stewart_inverse_output o;  // the fields read and written here (a memset of it costs more)
    get_row(out.length, j, o.lengths.length);
    get_row(out.length_rate, j, o.lengths.length_rate);
    get_row(out.length_accel, j, o.lengths.length_accel);
    get_row(out.force, j, o.force);
    fill_drive_outputs(drive, p, o);
    if (!drive_outputs_finite(o)) return false;
    STEWART_INVERSE_DRIVE_OUTPUT_TABLE(PUT)
    return true;
}

#undef PUT

namespace {

// d current / dt at row j of the solved run [first, last) (numpy.gradient, edge_order 1).
double current_rate_at(const double *current, const double *t, size_t first, size_t last, size_t j,
                       int k) {
    auto i = [&](size_t row) { return current[6 * row + k]; };
    if (last - first < 2) return 0;
    if (j == first) return (i(j + 1) - i(j)) / (t[j + 1] - t[j]);
    if (j + 1 == last) return (i(j) - i(j - 1)) / (t[j] - t[j - 1]);
    const double h1 = t[j] - t[j - 1], h2 = t[j + 1] - t[j];
    return (h1 * h1 * i(j + 1) - h2 * h2 * i(j - 1) + (h2 * h2 - h1 * h1) * i(j)) /
           (h1 * h2 * (h1 + h2));
}

}  // namespace

bool set_current_rates(const LegDrive (&drive)[STEWART_LEGS], const stewart_params &p,
                       const stewart_inverse_batch_outputs &out, size_t j,
                       const double (&rate)[STEWART_LEGS]) {
    double voltage[STEWART_LEGS], sum = 0;  // inf or NaN in a term: sum - sum is NaN
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const LegDrive &d = drive[k];
        const size_t e = 6 * j + k;
        voltage[k] = out.voltage[e];
        if (d.motor_per_leg == 0) continue;
        out.current_rate[e] = rate[k];
        voltage[k] = d.resistance * out.current[e] + d.torque_constant * out.motor_speed[e] +
                     d.inductance * rate[k];
        out.voltage[e] = voltage[k];
        if (out.electrical_power) out.electrical_power[e] = voltage[k] * out.current[e];
        sum += rate[k] + voltage[k] * out.current[e];
    }
    if (out.voltage_max_legs) out.voltage_max_legs[j] = legs_over(voltage, p.voltage_max);
    return sum - sum == 0;
}

size_t trajectory_current_rates(const LegDrive (&drive)[STEWART_LEGS], const stewart_params &p,
                                size_t n, const double *t,
                                const stewart_inverse_batch_outputs &out) {
    for (size_t first = 0; first < n;) {
        if (out.status[first] != STEWART_OK) {
            ++first;
            continue;
        }
        size_t last = first + 1;
        while (last < n && out.status[last] == STEWART_OK) ++last;
        for (size_t j = first; j < last; ++j) {
            double rate[STEWART_LEGS];
            for (int k = 0; k < STEWART_LEGS; ++k)
                rate[k] = current_rate_at(out.current, t, first, last, j, k);
            if (!set_current_rates(drive, p, out, j, rate)) return j;
        }
        first = last;
    }
    return n;
}

stewart_status jerk_current_rates(const LegDrive (&drive)[STEWART_LEGS], const stewart_params &p,
                                  stewart_linearize *lin, bool forces, size_t n, const double *q,
                                  const double *q_dot, const double *q_ddot, const double *q_dddot,
                                  const stewart_inverse_batch_outputs &out, char *msg,
                                  size_t size) {
    stewart_linearize_inverse_output d;
    for (size_t j = 0; j < n; ++j) {
        if (out.status[j] != STEWART_OK) continue;
        stewart_pose pose{};
        std::memcpy(pose.q, q + 6 * j, sizeof pose.q);
        if (q_dot) std::memcpy(pose.q_dot, q_dot + 6 * j, sizeof pose.q_dot);
        if (q_ddot) std::memcpy(pose.q_ddot, q_ddot + 6 * j, sizeof pose.q_ddot);
        const stewart_status s = stewart_linearize_inverse(lin, &pose, &d);
        if (s != STEWART_OK)
            return set_message(msg, size, s, "row %zu: the derivatives of its forces: %s", j,
                               stewart_linearize_message(lin));
        // The rates of the legs' accelerations (rows 12..17) and forces (rows 18..23): the
        // Jacobian times the pose's rate, acceleration and jerk.
        const double *motion[3] = {pose.q_dot, pose.q_ddot, q_dddot + 6 * j};
        double rate[STEWART_LEGS];
        for (int k = 0; k < STEWART_LEGS; ++k) {
            double jerk = 0, force_rate = 0;
            for (int c = 0; c < 18; ++c) {
                jerk += d.jacobian[12 + k][c] * motion[c / 6][c % 6];
                force_rate += d.jacobian[18 + k][c] * motion[c / 6][c % 6];
            }
            const size_t e = 6 * j + k;
            const LegDrive &dk = drive[k];
            rate[k] = dk.motor_per_leg == 0
                          ? 0.0
                          : drive_torque_rate(dk, out.force[e], forces ? force_rate : 0.0,
                                              out.length_rate[e], out.length_accel[e], jerk) /
                                dk.torque_constant;
        }
        if (!set_current_rates(drive, p, out, j, rate))
            return set_message(msg, size, STEWART_ERR_ARGUMENT,
                               "row %zu: its jerk makes a current's rate or the voltage overflow: "
                               "give jerks (q_dddot) of the size the motion has",
                               j);
    }
    return STEWART_OK;
}

}  // namespace stewart
