/* The plant driven by motor currents and voltages, against laws written here from the
 * parameters: the vertical motion of a symmetric platform in closed form (each drive term alone),
 * the power balance of the motors, the bodies, the rotors and the losses over 10 s, the end stop
 * holding a leg at full current, and force input that ignores the drives bit for bit. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "stewart/stewart_plant.h"
#include "test_plant_support.h"
#include "test_support.h"
#include "unity.h"

static stewart_params params;
static stewart_model *model;

/* A drive on every leg: 5 mm lead, gear 3, a servo motor (k_t 0.5 N m/A, R 1.2 ohm). */
static void with_drives(stewart_params *p) {
    for (int k = 0; k < 6; ++k) {
        p->screw_lead[k] = 0.005;
        p->gear_ratio[k] = 3;
        p->rotor_inertia[k] = 2e-5;
        p->screw_inertia[k] = 9e-5;
        p->torque_constant[k] = 0.5;
        p->winding_resistance[k] = 1.2;
        p->screw_efficiency[k] = 0.9;
        p->screw_back_efficiency[k] = 0.8;
        p->coulomb_friction[k] = 40;
        p->stribeck_friction[k] = 60;
        p->stribeck_speed[k] = 0.01;
        p->viscous_friction[k] = 300;
    }
}

void setUp(void) {
    stewart_params_default(&params);
    with_drives(&params);
    model = NULL;
}

void tearDown(void) {
    stewart_model_free(model);
    model = NULL;
}

static stewart_plant *driven_plant(int fidelity, int input, double smoothing_speed) {
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    o.fidelity = fidelity;
    o.input = input;
    o.smoothing_speed = smoothing_speed;
    o.relative_tolerance = 1e-12;
    o.absolute_tolerance = 1e-14;
    o.max_internal_steps = 100000;
    char msg[STEWART_MESSAGE_SIZE];
    stewart_plant *p = stewart_plant_create(model, &o, msg, sizeof msg);
    if (!p) TEST_FAIL_MESSAGE(msg);
    return p;
}

/* The drive's law as docs/forward-dynamics.md states it, written here. */
static double motor_per_leg(int k) {
    return 2 * M_PI * params.gear_ratio[k] / params.screw_lead[k];
}
static double motor_inertia(int k) {
    const double N = params.gear_ratio[k];
    return params.rotor_inertia[k] + params.screw_inertia[k] / (N * N);
}
static double smooth(double v, double vs) { return v / sqrt(v * v + vs * vs); }
static double friction(int k, double v, double vs) {
    const double x = v / params.stribeck_speed[k];
    const double sliding = params.coulomb_friction[k] +
                           (params.stribeck_friction[k] - params.coulomb_friction[k]) * exp(-x * x);
    return sliding * smooth(v, vs) + params.viscous_friction[k] * v;
}
/* The factor e of F_nut = e F_i for power flow x = sign(F_i) s(v). */
static double efficiency(int k, double x) {
    return x >= 0 ? 1 + (params.screw_efficiency[k] - 1) * x
                  : 1 - (1 / params.screw_back_efficiency[k] - 1) * x;
}

/* ---- vertical motion of the symmetric platform, massless legs: closed form ---- */

/* The inverse side (massless level, a separate formulation) at the vertical motion (z, z_dot,
 * z_ddot): lengths, rates, accelerations and the forces it needs. */
static void inverse_vertical(double z, double z_dot, double z_ddot, stewart_inverse_output *out) {
    stewart_inverse_options o;
    stewart_inverse_options_default(&o);
    o.fidelity = STEWART_MASSLESS;
    char msg[STEWART_MESSAGE_SIZE];
    stewart_inverse *inv = stewart_inverse_create(model, &o, msg, sizeof msg);
    if (!inv) TEST_FAIL_MESSAGE(msg);
    stewart_inverse_input in;
    memset(&in, 0, sizeof in);
    in.pose.q[2] = z;
    in.pose.q_dot[2] = z_dot;
    in.pose.q_ddot[2] = z_ddot;
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_inverse_solve(inv, &in, out));
    stewart_inverse_free(inv);
}

/* z_ddot under the same input u (current, or voltage when `voltage`) on all six legs: the leg
 * force the mechanism needs is F_0 + F_1 z_ddot (inverse side), the drive gives
 * e (c k_t i - m_r (n_z z_ddot + a)) - friction with n_z = dL/dz, a = L_ddot at z_ddot = 0;
 * equal them on the efficiency branch that is consistent (sign of F_i). */
static double vertical_accel(double z, double z_dot, double u, int voltage, double vs) {
    stewart_inverse_output at0, at1;
    inverse_vertical(z, z_dot, 0, &at0);
    inverse_vertical(z, z_dot, 1, &at1);
    const int k = 0;
    const double L_dot = at0.lengths.length_rate[k], a = at0.lengths.length_accel[k];
    const double n_z = at1.lengths.length_accel[k] - a;
    const double F0 = at0.force[k], F1 = at1.force[k] - F0;
    const double c = motor_per_leg(k), m_r = motor_inertia(k) * c * c,
                 kt = params.torque_constant[k];
    const double i = voltage ? (u - kt * c * L_dot) / params.winding_resistance[k] : u;
    const double f = friction(k, L_dot, vs), s = smooth(L_dot, vs);
    for (int sign = 1; sign >= -1; sign -= 2) {
        const double e = efficiency(k, sign * s);
        /* e (c kt i - m_r a) - e m_r n_z zdd - f = F0 + F1 zdd */
        const double zdd = (e * (c * kt * i - m_r * a) - f - F0) / (F1 + e * m_r * n_z);
        const double ideal = c * kt * i - m_r * (n_z * zdd + a);
        if ((ideal >= 0) == (sign > 0)) return zdd;
    }
    TEST_FAIL_MESSAGE("no consistent efficiency branch");
    return 0;
}

static double plant_vertical_accel(stewart_plant *plant, double z, double z_dot, double u,
                                   double *off_axis) {
    stewart_plant_derivative_input in;
    memset(&in, 0, sizeof in);
    in.pose.q[2] = z;
    in.pose.q_dot[2] = z_dot;
    for (int k = 0; k < 6; ++k) in.force[k] = u;
    stewart_plant_output out;
    TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK, stewart_plant_derivatives(plant, &in, &out),
                              stewart_plant_message(plant));
    *off_axis = 0;
    for (int j = 0; j < 6; ++j)
        if (j != 2 && fabs(out.pose.q_ddot[j]) > *off_axis) *off_axis = fabs(out.pose.q_ddot[j]);
    return out.pose.q_ddot[2];
}

/* One term at a time: lossless with inertia only; forward efficiency (rising, motor lifting);
 * back efficiency (sinking under a holding current); friction alone; back-EMF (voltage input). */
static void vertical_case(const char *what, double eta, double eta_back, double coulomb,
                          double viscous, double z_dot, double u, int voltage) {
    for (int k = 0; k < 6; ++k) {
        params.screw_efficiency[k] = eta;
        params.screw_back_efficiency[k] = eta_back;
        params.coulomb_friction[k] = coulomb;
        params.stribeck_friction[k] = coulomb > 0 ? 1.5 * coulomb : 0;
        params.viscous_friction[k] = viscous;
    }
    stewart_model_free(model);
    model = test_model(&params);
    const double vs = 1e-4;
    stewart_plant *plant = driven_plant(STEWART_MASSLESS, voltage ? 2 : 1, vs);
    const double z = 0.55;
    double off_axis;
    const double got = plant_vertical_accel(plant, z, z_dot, u, &off_axis);
    const double want = vertical_accel(z, z_dot, u, voltage, vs);
    printf("vertical, %s: z_ddot = %.12g (closed form %.12g), off-axis %.2g\n", what, got, want,
           off_axis);
    TEST_ASSERT_DOUBLE_WITHIN(1e-11 * (1 + fabs(want)), want, got);
    TEST_ASSERT_TRUE(off_axis < 1e-10);
    stewart_plant_free(plant);
}

static void test_vertical_terms(void) {
    for (int k = 0; k < 6; ++k) params.winding_resistance[k] = 1.2;
    /* hold current of this platform: about (m g / 6 / n_z) / (c k_t) */
    vertical_case("inertia only", 1, 1, 0, 0, 0.05, 0.4, 0);
    vertical_case("forward efficiency", 0.9, 1, 0, 0, 0.05, 0.6, 0);
    vertical_case("back efficiency", 1, 0.7, 0, 0, -0.05, 0.1, 0);
    vertical_case("friction", 1, 1, 40, 300, 0.05, 0.4, 0);
    vertical_case("friction, near rest", 1, 1, 40, 300, 3e-5, 0.4, 0);
    vertical_case("back-EMF (voltage)", 1, 1, 0, 0, 0.05, 24, 1);
    vertical_case("all terms, sinking", 0.9, 0.8, 40, 300, -0.03, 0.2, 0);
}

/* ---- power balance ---- */

/* What the test reads at one instant: the motors' power in, the losses (friction, the screw's),
 * and the stored energy of bodies, rotors and end-stop springs. */
typedef struct {
    double motor_power, loss_power, stored;
} energy_point;

static energy_point energy_at(const stewart_plant *plant, int fidelity, double vs, int input) {
    stewart_plant_output out;
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &out));
    double T, U;
    plant_energy(&params, plant, fidelity, &T, &U);
    energy_point e = {0, 0, T + U};
    for (int k = 0; k < 6; ++k) {
        const double c = motor_per_leg(k), v = out.lengths.length_rate[k];
        const double L = out.lengths.length[k] + params.length_offset[k];
        const double omega = c * v;
        TEST_ASSERT_DOUBLE_WITHIN(1e-12 * (1 + fabs(omega)), omega, out.motor_speed[k]);
        if (input == STEWART_PLANT_INPUT_VOLTAGE) {
            /* the terminals' power; the winding's copper loss and magnetic energy */
            const double i = out.current[k], L_w = params.winding_inductance[k];
            e.motor_power += out.voltage[k] * i;
            e.loss_power += params.winding_resistance[k] * i * i;
            e.stored += 0.5 * L_w * i * i;
        } else {
            e.motor_power += params.torque_constant[k] * out.current[k] * omega;
        }
        e.stored += 0.5 * motor_inertia(k) * omega * omega;
        double stop = 0, spring = 0;
        const double kst = params.end_stop_stiffness[k], dst = params.end_stop_damping[k];
        /* spring k delta, damper d v limited to +-k delta */
        if (L > params.stroke_max[k]) {
            const double depth = L - params.stroke_max[k];
            stop = -(kst * depth + fmax(-kst * depth, fmin(kst * depth, dst * v)));
            spring = 0.5 * kst * depth * depth;
        } else if (L < params.stroke_min[k]) {
            const double depth = params.stroke_min[k] - L;
            stop = kst * depth + fmax(-kst * depth, fmin(kst * depth, -dst * v));
            spring = 0.5 * kst * depth * depth;
        }
        e.stored += spring;
        const double f = friction(k, v, vs);
        const double nut = out.force[k] + f - stop;
        const double eff = efficiency(k, (nut >= 0 ? 1 : -1) * smooth(v, vs));
        /* friction loss f v; screw loss F_i v - F_nut v = (1/e - 1) F_nut v */
        /* the stop's damper: its power less the spring's (d/dt of the energy stored above) */
        const double spring_power = L > params.stroke_max[k] ? kst * (L - params.stroke_max[k]) * v
                                    : L < params.stroke_min[k]
                                        ? -kst * (params.stroke_min[k] - L) * v
                                        : 0;
        e.loss_power += f * v + (1 / eff - 1) * nut * v - stop * v - spring_power;
    }
    return e;
}

/* Runs `seconds` with 1 ms communication steps, the current held linear over each step (a PD on
 * the lengths, one step late, around hold + amplitude sin), and integrates the powers by Simpson
 * over each step (kPanels plant steps, even). Returns the largest |E_in - losses - dE| over the
 * run, relative to the energy moved (the integrated |motor power|); *max_penetration: the
 * largest length beyond stroke_max over the second half of the run. amplitude 0: no loop, the
 * current held at `hold`. */
static double power_balance(int fidelity, int input, double seconds, double hold, double amplitude,
                            double vs, int kPanels, double *max_penetration, double *unaccounted) {
    model = test_model(&params);
    stewart_plant *plant = driven_plant(fidelity, input, vs);
    stewart_plant_output out;
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &out));
    double L0[6];
    for (int k = 0; k < 6; ++k) L0[k] = out.lengths.length[k];
    const double h = 1e-3;
    double i_now[6], i_next[6];
    for (int k = 0; k < 6; ++k)
        i_now[k] =
            input == STEWART_PLANT_INPUT_VOLTAGE ? params.winding_resistance[k] * hold : hold;
    energy_point e0 = energy_at(plant, fidelity, vs, input);
    const double stored0 = e0.stored;
    double in = 0, lost = 0, moved = 0, worst = 0;
    *max_penetration = 0;
    const int n = (int)(seconds / h + 0.5);
    for (int step = 0; step < n; ++step) {
        const double t = step * h;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &out));
        for (int k = 0; k < 6; ++k) {
            const double ref = L0[k] + amplitude * sin(2 * M_PI * 0.5 * (t + h) + k);
            i_next[k] = amplitude == 0 ? hold /* no loop: held at that current */
                                       : hold + 40 * (ref - out.lengths.length[k]) -
                                             4 * out.lengths.length_rate[k];
            if (input == STEWART_PLANT_INPUT_VOLTAGE) /* that current, and the back-EMF */
                i_next[k] = params.winding_resistance[k] * i_next[k] +
                            params.torque_constant[k] * out.motor_speed[k];
        }
        /* composite Simpson over kPanels sub-steps, the current linear across them */
        energy_point e1 = e0;
        double w_in = e0.motor_power, w_lost = e0.loss_power, w_moved = fabs(e0.motor_power);
        for (int j = 1; j <= kPanels; ++j) {
            double ia[6], ib[6];
            for (int k = 0; k < 6; ++k) {
                ia[k] = i_now[k] + (i_next[k] - i_now[k]) * (j - 1) / kPanels;
                ib[k] = i_now[k] + (i_next[k] - i_now[k]) * j / kPanels;
            }
            step_ok(plant, h / kPanels, ia, ib, NULL, NULL);
            e1 = energy_at(plant, fidelity, vs, input);
            const double w = j == kPanels ? 1 : j % 2 ? 4 : 2;
            w_in += w * e1.motor_power;
            w_lost += w * e1.loss_power;
            w_moved += w * fabs(e1.motor_power);
        }
        in += h / kPanels / 3 * w_in;
        lost += h / kPanels / 3 * w_lost;
        moved += h / kPanels / 3 * w_moved;
        const double miss = fabs(in - lost - (e1.stored - stored0));
        if (miss > worst) worst = miss;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &out));
        for (int k = 0; k < 6; ++k) {
            const double over =
                out.lengths.length[k] + params.length_offset[k] - params.stroke_max[k];
            if (t >= 0.5 * seconds && over > *max_penetration) *max_penetration = over;
        }
        e0 = e1;
        for (int k = 0; k < 6; ++k) i_now[k] = i_next[k];
    }
    printf("power balance, fidelity %d, %.0f s, smoothing %g m/s: energy in %.6g J, losses %.6g J, "
           "stored %+.6g J, moved %.6g J, worst |in - losses - stored| %.3g J (%.3g relative)\n",
           fidelity, seconds, vs, in, lost, e0.stored - stored0, moved, worst, worst / moved);
    *unaccounted = in - lost - (e0.stored - stored0);
    stewart_plant_free(plant);
    return worst / moved;
}

static void test_power_balance_full(void) {
    double penetration, unaccounted;
    const double miss = power_balance(STEWART_FULL, STEWART_PLANT_INPUT_CURRENT, 10, 0.45, 0.01,
                                      1e-2, 4, &penetration, &unaccounted);
    TEST_ASSERT_TRUE(miss < 1e-9);
}

static void test_power_balance_massless_default_smoothing(void) {
    double penetration, unaccounted;
    const double miss = power_balance(STEWART_MASSLESS, STEWART_PLANT_INPUT_CURRENT, 10, 0.45, 0.01,
                                      1e-4, 4, &penetration, &unaccounted);
    TEST_ASSERT_TRUE(miss < 1e-7);
}

/* Voltage input with the windings' currents as states (inductance 5 mH, L/R = 4.2 ms): the
 * terminals' power V i = copper loss R i^2 + d/dt(1/2 L i^2) + the motor's k_t i omega, and that
 * as above: the balance over 10 s, and the voltage's winding current rising as the RL law says at
 * the first steps from rest. */
static void test_power_balance_voltage_with_inductance(void) {
    for (int k = 0; k < 6; ++k) params.winding_inductance[k] = 5e-3;
    double penetration, unaccounted;
    const double miss = power_balance(STEWART_FULL, STEWART_PLANT_INPUT_VOLTAGE, 10, 0.45, 0.01,
                                      1e-2, 16, &penetration, &unaccounted);
    TEST_ASSERT_TRUE(miss < 1e-9);
}

/* From rest without gravity, a voltage V on a winding with inductance: i(t) = V/R (1 -
 * exp(-R t / L)) while the back-EMF is negligible: the current's force moves the legs as t^2, so
 * the back-EMF's share is k_t^2 c^2 t^2 / (2 L m), m the leg's share of the moving mass with its
 * reflected mass (about 2000 kg here): 4e-4 at 50 us. */
static void test_winding_current_follows_the_rl_law(void) {
    for (int k = 0; k < 6; ++k) params.winding_inductance[k] = 5e-3;
    params.gravity[2] = 0;
    model = test_model(&params);
    stewart_plant *plant = driven_plant(STEWART_FULL, STEWART_PLANT_INPUT_VOLTAGE, 1e-4);
    const double V[6] = {1, 1, 1, 1, 1, 1};
    double worst = 0;
    for (int step = 1; step <= 5; ++step) {
        step_ok(plant, 1e-5, V, V, NULL, NULL);
        stewart_plant_output out;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &out));
        const double t = 1e-5 * step, R = params.winding_resistance[0], L = 5e-3;
        const double want = 1.0 / R * (1 - exp(-R * t / L));
        worst = fmax(worst, fabs(out.current[0] - want) / want);
        TEST_ASSERT_DOUBLE_WITHIN(1e-15, 1.0, out.voltage[0]);
    }
    printf("RL law: winding current within %.3g relative over 50 us\n", worst);
    TEST_ASSERT_TRUE(worst < 1e-3); /* the back-EMF's share */
    /* a saved state holds the currents: a rollback repeats the next step bit for bit */
    unsigned char saved[512];
    TEST_ASSERT_TRUE(stewart_plant_state_size(plant) <= sizeof saved);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_save(plant, saved, sizeof saved));
    stewart_plant_output first, again;
    stewart_plant_input in;
    memset(&in, 0, sizeof in);
    in.h = 1e-3;
    for (int k = 0; k < 6; ++k) in.force_start[k] = 1, in.force_end[k] = 2;
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_step(plant, &in, &first));
    TEST_ASSERT_EQUAL(STEWART_OK,
                      stewart_plant_load(plant, saved, stewart_plant_state_size(plant)));
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_step(plant, &in, &again));
    TEST_ASSERT_EQUAL_MEMORY(&first, &again, sizeof first);
    stewart_plant_free(plant);
}

/* Every leg driven at full current into its upper stop: held within F/k + 1e-9 m of it (F the
 * motor's force through the lossless screw: an upper bound of the nut's), and the energy balance
 * leaves the stops' dampers a loss >= 0 (no energy made). */
static void test_end_stop_holds_full_current(void) {
    const double i_max = 3.0;
    for (int k = 0; k < 6; ++k) {
        params.current_max[k] = i_max;
        params.end_stop_stiffness[k] = 1e8;
        params.end_stop_damping[k] = 5e5; /* about critical with the reflected mass */
    }
    double penetration, unaccounted;
    const double miss = power_balance(STEWART_FULL, STEWART_PLANT_INPUT_CURRENT, 1.0, i_max, 0.0,
                                      1e-2, 16, &penetration, &unaccounted);
    const double F = motor_per_leg(0) * params.torque_constant[0] * i_max;
    printf("end stop: penetration %.9g m, F/k = %.9g m; energy in - losses - stored at the end "
           "%.6g J; worst relative %.3g\n",
           penetration, F / 1e8, unaccounted, miss);
    TEST_ASSERT_TRUE(penetration > 0);
    TEST_ASSERT_TRUE(penetration <= F / 1e8 + 1e-9);
    /* the contact's kinks (the spring at delta = 0, the damper's limits) leave Simpson at
       62.5 us about 1e-4 of the energy moved: the balance holds to that, not to 1e-9 */
    TEST_ASSERT_TRUE(miss < 2e-4);
}

/* ---- joint reactions with driven legs ---- */

/* The base Cardans' reactions (which carry the legs' axial forces the drives made, not the
 * currents) add up to the base wrench the plant reports, the momentum balance of the bodies. */
static void test_reactions_carry_the_drives_forces(void) {
    model = test_model(&params);
    stewart_plant *plant = driven_plant(STEWART_FULL, STEWART_PLANT_INPUT_CURRENT, 1e-4);
    double i0[6], i1[6];
    for (int k = 0; k < 6; ++k) i0[k] = 0.45;
    double worst = 0;
    for (int step = 0; step < 200; ++step) {
        for (int k = 0; k < 6; ++k) i1[k] = 0.45 + 0.05 * sin(0.05 * step + k);
        step_ok(plant, 1e-3, i0, i1, NULL, NULL);
        for (int k = 0; k < 6; ++k) i0[k] = i1[k];
        if (step % 40 != 39) continue;
        stewart_plant_output out;
        stewart_plant_reactions r;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &out));
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_reactions_get(plant, NULL, &r));
        worst = fmax(worst, base_wrench_error(&params, &r, &out));
    }
    printf("reactions with drives: base wrench %.3g N or N m off the base Cardans' sum\n", worst);
    TEST_ASSERT_TRUE(worst <= 1e-9);
    stewart_plant_free(plant);
}

/* ---- force input: the drives are not used, bit for bit ---- */

static void run_bytes(const stewart_params *p, int set_input, unsigned char *bytes, size_t size) {
    stewart_model *m = test_model(p);
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    if (set_input) o.input = STEWART_PLANT_INPUT_FORCE;
    char msg[STEWART_MESSAGE_SIZE];
    stewart_plant *plant = stewart_plant_create(m, &o, msg, sizeof msg);
    if (!plant) TEST_FAIL_MESSAGE(msg);
    const size_t each = sizeof(stewart_plant_output);
    for (size_t i = 0; (i + 1) * each <= size; ++i) {
        double f0[6], f1[6];
        for (int k = 0; k < 6; ++k) {
            f0[k] = 1000 + 50 * sin(0.01 * i + k);
            f1[k] = 1000 + 50 * sin(0.01 * (i + 1) + k);
        }
        stewart_plant_input in;
        memset(&in, 0, sizeof in);
        in.h = 1e-3;
        memcpy(in.force_start, f0, sizeof f0);
        memcpy(in.force_end, f1, sizeof f1);
        stewart_plant_output out;
        memset(&out, 0, sizeof out);
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_step(plant, &in, &out));
        memcpy(bytes + i * each, &out, each);
    }
    stewart_plant_free(plant);
    stewart_model_free(m);
}

static void test_force_input_ignores_drives_bit_for_bit(void) {
    enum { kSteps = 300 };
    static unsigned char without[kSteps * sizeof(stewart_plant_output)];
    static unsigned char with[kSteps * sizeof(stewart_plant_output)];
    stewart_params plain;
    stewart_params_default(&plain);
    run_bytes(&plain, 0, without, sizeof without);
    run_bytes(&params, 1, with, sizeof with);
    TEST_ASSERT_EQUAL_MEMORY(without, with, sizeof without);
}

/* ---- refusals ---- */

/* Leg k without a drive: its motor, screw and friction parameters back at their defaults (the
 * parameter check refuses them on a leg without a screw). */
static void without_drive(stewart_params *p, int k) {
    p->screw_lead[k] = p->rotor_inertia[k] = p->screw_inertia[k] = 0;
    p->torque_constant[k] = p->winding_resistance[k] = 0;
    p->gear_ratio[k] = p->screw_efficiency[k] = p->screw_back_efficiency[k] = 1;
    p->coulomb_friction[k] = p->stribeck_friction[k] = p->stribeck_speed[k] = 0;
    p->viscous_friction[k] = 0;
}

static void test_current_input_needs_a_drive_on_every_leg(void) {
    without_drive(&params, 3);
    model = test_model(&params);
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    o.input = STEWART_PLANT_INPUT_CURRENT;
    char msg[STEWART_MESSAGE_SIZE];
    TEST_ASSERT_NULL(stewart_plant_create(model, &o, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL(strstr(msg, "screw_lead[4]"));
    with_drives(&params);
    params.winding_resistance[2] = 0;
    stewart_model_free(model);
    model = test_model(&params);
    o.input = STEWART_PLANT_INPUT_VOLTAGE;
    TEST_ASSERT_NULL(stewart_plant_create(model, &o, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL(strstr(msg, "winding_resistance[3]"));
    /* the windings' currents as states: the derivative call, which takes no such state, says so */
    params.winding_resistance[2] = 1.2;
    params.winding_inductance[2] = 1e-3;
    stewart_model_free(model);
    model = test_model(&params);
    stewart_plant *plant = stewart_plant_create(model, &o, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(plant, msg);
    stewart_plant_derivative_input in;
    memset(&in, 0, sizeof in);
    in.pose.q[2] = 0.5;
    stewart_plant_output out;
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, stewart_plant_derivatives(plant, &in, &out));
    TEST_ASSERT_NOT_NULL(strstr(stewart_plant_message(plant), "winding_inductance"));
    stewart_plant_free(plant);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_vertical_terms);
    RUN_TEST(test_power_balance_full);
    RUN_TEST(test_power_balance_massless_default_smoothing);
    RUN_TEST(test_end_stop_holds_full_current);
    RUN_TEST(test_power_balance_voltage_with_inductance);
    RUN_TEST(test_winding_current_follows_the_rl_law);
    RUN_TEST(test_reactions_carry_the_drives_forces);
    RUN_TEST(test_force_input_ignores_drives_bit_for_bit);
    RUN_TEST(test_current_input_needs_a_drive_on_every_leg);
    return UNITY_END();
}
