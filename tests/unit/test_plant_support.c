#include "test_plant_support.h"

#include <math.h>
#include <string.h>
#include <stdio.h>

#include "test_support.h"
#include "unity.h"

stewart_plant *test_plant(const stewart_model *model, int fidelity, double rtol, double atol) {
    stewart_plant_options o = test_plant_options(fidelity);
    o.relative_tolerance = rtol;
    o.absolute_tolerance = atol;
    o.max_internal_steps = 100000;
    return test_plant_with(model, &o);
}

/* 1/2 m v.v + 1/2 w.(A I A^T) w, and -m g.r, for one body with principal inertia I. */
static void body_energy(const stewart_plant_body *b, double mass, const double inertia[3],
                        const double gravity[3], double *kinetic, double *potential) {
    double w_body[3]; /* omega in the body axes: A^T w */
    for (int j = 0; j < 3; ++j)
        w_body[j] = b->rotation[0 * 3 + j] * b->omega[0] + b->rotation[1 * 3 + j] * b->omega[1] +
                    b->rotation[2 * 3 + j] * b->omega[2];
    double t = 0, u = 0;
    for (int i = 0; i < 3; ++i) {
        t +=
            0.5 * mass * b->velocity[i] * b->velocity[i] + 0.5 * inertia[i] * w_body[i] * w_body[i];
        u -= mass * gravity[i] * b->position[i];
    }
    *kinetic += t;
    *potential += u;
}

void plant_energy(const stewart_params *p, const stewart_plant *plant, int fidelity,
                  double *kinetic, double *potential) {
    TEST_ASSERT_EQUAL_DOUBLE(0.0, p->payload_mass);
    stewart_plant_body bodies[STEWART_PLANT_BODIES];
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_bodies(plant, bodies));
    *kinetic = *potential = 0;
    body_energy(&bodies[0], p->platform_mass, p->platform_inertia, p->gravity, kinetic, potential);
    if (fidelity != STEWART_FULL) return;
    for (int k = 0; k < 6; ++k) {
        body_energy(&bodies[1 + k], p->cylinder_mass, p->cylinder_inertia, p->gravity, kinetic,
                    potential);
        body_energy(&bodies[7 + k], p->piston_mass, p->piston_inertia, p->gravity, kinetic,
                    potential);
    }
}

void step_ok(stewart_plant *plant, double h, const double f0[6], const double f1[6],
             const double r0[6], const double r1[6]) {
    const stewart_status s = plant_step_arrays(plant, h, f0, f1, r0, r1);
    if (s != STEWART_OK) {
        char text[STEWART_MESSAGE_SIZE + 64];
        snprintf(text, sizeof text, "%s: %s", stewart_status_name(s), stewart_plant_message(plant));
        TEST_FAIL_MESSAGE(text);
    }
}

void heavy_legs(stewart_params *p) {
    const double m = 10.0, r = 0.05, l = 0.3;
    p->cylinder_mass = p->piston_mass = m;
    p->cylinder_inertia[0] = p->cylinder_inertia[1] = m * (3 * r * r + l * l) / 12.0;
    p->cylinder_inertia[2] = m * r * r / 2.0;
    for (int i = 0; i < 3; ++i) p->piston_inertia[i] = p->cylinder_inertia[i];
}

static double dot3(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Column c of a row-major 3x3 rotation. */
static void column(const double R[9], int c, double out[3]) {
    for (int i = 0; i < 3; ++i) out[i] = R[3 * i + c];
}

static void worse(double *worst, double e) {
    if (fabs(e) > *worst) *worst = fabs(e);
}

double leg_joint_error(const stewart_params *params, const double pose_q[6],
                       const stewart_plant_body bodies[STEWART_PLANT_BODIES]) {
    stewart_pose pose = {{0}, {0}, {0}};
    for (int c = 0; c < 6; ++c) pose.q[c] = pose_q[c];
    double R[3][3];
    pose_rotation(&pose, R);
    double worst = 0;
    for (int k = 0; k < 6; ++k) {
        const stewart_plant_body *cyl = &bodies[1 + k], *pis = &bodies[7 + k];
        double zc[3], zp[3], xc[3], xp[3];
        column(cyl->rotation, 2, zc);
        column(pis->rotation, 2, zp);
        column(cyl->rotation, 0, xc);
        column(pis->rotation, 0, xp);
        const double a[3] = {params->base_radius * cos(params->base_angle[k]),
                             params->base_radius * sin(params->base_angle[k]), 0};
        const double b[3] = {params->platform_radius * cos(params->platform_angle[k]),
                             params->platform_radius * sin(params->platform_angle[k]), 0};
        const double s_base[3] = {-sin(params->base_angle[k]), cos(params->base_angle[k]), 0};
        const double s_plate[3] = {-sin(params->platform_angle[k]), cos(params->platform_angle[k]),
                                   0};
        double s_plate_world[3], gap[3];
        for (int r = 0; r < 3; ++r) {
            const double P = pose.q[r] + R[r][0] * b[0] + R[r][1] * b[1];
            s_plate_world[r] = R[r][0] * s_plate[0] + R[r][1] * s_plate[1];
            /* Cardan centres, and one common axis */
            worse(&worst, cyl->position[r] - params->cylinder_com * zc[r] - a[r]);
            worse(&worst, pis->position[r] + params->piston_com * zp[r] - P);
            worse(&worst, zc[r] - zp[r]);
            gap[r] = pis->position[r] - cyl->position[r];
        }
        /* cylindrical: the offset between the bodies lies along the common axis */
        const double along = dot3(gap, zc);
        for (int r = 0; r < 3; ++r) worse(&worst, gap[r] - along * zc[r]);
        /* Cardan cross arms perpendicular */
        worse(&worst, dot3(xc, s_base));
        worse(&worst, dot3(xp, s_plate_world));
    }
    return worst;
}

stewart_status plant_step_arrays(stewart_plant *plant, double h, const double f0[6],
                                 const double f1[6], const double r0[6], const double r1[6]) {
    stewart_plant_output out;
    if (!f0 || !f1) return stewart_plant_step(plant, NULL, &out);
    stewart_plant_input in;
    memset(&in, 0, sizeof in);
    in.h = h;
    memcpy(in.force_start, f0, sizeof in.force_start);
    memcpy(in.force_end, f1, sizeof in.force_end);
    in.derivatives = r0 && r1 ? 1 : (r0 || r1) ? 2 : 0; /* 2: refused, as one rate array alone */
    if (r0) memcpy(in.force_rate_start, r0, sizeof in.force_rate_start);
    if (r1) memcpy(in.force_rate_end, r1, sizeof in.force_rate_end);
    return stewart_plant_step(plant, &in, &out);
}

/* The header of a saved state: the bytes before its doubles. */
static size_t header_bytes(const stewart_plant *plant) {
    return stewart_plant_state_size(plant) - sizeof(double) * plant_state_doubles();
}

size_t plant_state_doubles(void) {
    return 25;
} /* time, 13 state values, 3 angles, 6 forces, warnings, step hint */

void plant_save_doubles(const stewart_plant *plant, double *state) {
    unsigned char bytes[1024];
    const size_t size = stewart_plant_state_size(plant);
    TEST_ASSERT_TRUE(size <= sizeof bytes);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_save(plant, bytes, size));
    memcpy(state, bytes + header_bytes(plant), size - header_bytes(plant));
}

stewart_status plant_load_doubles(stewart_plant *plant, const double *state, size_t count) {
    unsigned char bytes[1024];
    const size_t size = stewart_plant_state_size(plant), header = header_bytes(plant);
    TEST_ASSERT_TRUE(header + count * sizeof(double) <= sizeof bytes);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_save(plant, bytes, size)); /* its header */
    memcpy(bytes + header, state, count * sizeof(double));
    return stewart_plant_load(plant, bytes, header + count * sizeof(double));
}

double base_wrench_error(const stewart_params *params, const stewart_plant_reactions *r,
                         const stewart_plant_output *out) {
    double worst = 0;
    for (int a = 0; a < 3; ++a) {
        double force = 0, torque = 0;
        for (int k = 0; k < 6; ++k) {
            const double p[3] = {params->base_radius * cos(params->base_angle[k]),
                                 params->base_radius * sin(params->base_angle[k]), 0};
            const double *fb = r->base_cardan_force[k];
            const double moment[3] = {p[1] * fb[2] - p[2] * fb[1], p[2] * fb[0] - p[0] * fb[2],
                                      p[0] * fb[1] - p[1] * fb[0]};
            force -= fb[a];
            torque -= moment[a] + r->base_cardan_torque[k][a];
        }
        worst =
            fmax(worst, fmax(fabs(force - out->base_force[a]), fabs(torque - out->base_torque[a])));
    }
    return worst;
}
