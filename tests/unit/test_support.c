#include "test_support.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "unity.h"

/* object, or the test fails with the library's message when it could not be made. */
static void *made(void *object, const char *msg) {
    if (!object) TEST_FAIL_MESSAGE(msg);
    return object;
}

stewart_model *test_model(const stewart_params *params) {
    char msg[STEWART_MESSAGE_SIZE];
    return made(stewart_model_create(params, msg, sizeof msg), msg);
}

stewart_inverse_options test_options(stewart_fidelity fidelity) {
    stewart_inverse_options o;
    stewart_inverse_options_default(&o);
    o.fidelity = fidelity;
    return o;
}

static void sinusoid(stewart_pose *p, int i, double mean, double amp, double w, double phase,
                     double t) {
    p->q[i] = mean + amp * sin(w * t + phase);
    p->q_dot[i] = amp * w * cos(w * t + phase);
    p->q_ddot[i] = -amp * w * w * sin(w * t + phase);
}

stewart_pose combined_pose(double t) {
    stewart_pose p = {{0}, {0}, {0}};
    sinusoid(&p, 0, 0.00, 0.05, 3.0, 0.1, t);
    sinusoid(&p, 1, 0.00, 0.04, 2.0, 0.7, t);
    sinusoid(&p, 2, 0.50, 0.03, 4.0, 0.3, t);
    sinusoid(&p, 3, 0.00, 0.10, 2.5, 1.1, t);
    sinusoid(&p, 4, 0.00, 0.08, 3.5, 0.4, t);
    sinusoid(&p, 5, 0.00, 0.15, 1.5, 0.9, t);
    return p;
}

stewart_pose thesis_pose(int component, double t) {
    stewart_pose p = {{0}, {0}, {0}};
    p.q[2] = 0.5;
    if (component == 2) sinusoid(&p, 2, 0.5, 0.04, 5.0, 0.0, t);
    else sinusoid(&p, component, 0.0, M_PI / 18.0, 5.0, 0.0, t);
    return p;
}

void pose_rotation(const stewart_pose *pose, double R[3][3]) {
    const double cr = cos(pose->q[3]), sr = sin(pose->q[3]), cp = cos(pose->q[4]),
                 sp = sin(pose->q[4]), cy = cos(pose->q[5]), sy = sin(pose->q[5]);
    R[0][0] = cy * cp, R[0][1] = cy * sp * sr - sy * cr, R[0][2] = cy * sp * cr + sy * sr;
    R[1][0] = sy * cp, R[1][1] = sy * sp * sr + cy * cr, R[1][2] = sy * sp * cr - cy * sr;
    R[2][0] = -sp, R[2][1] = cp * sr, R[2][2] = cp * cr;
}

double closed_form_length(const stewart_params *params, const stewart_pose *pose, int k) {
    double R[3][3];
    pose_rotation(pose, R);
    double a[3] = {params->base_radius * cos(params->base_angle[k]),
                   params->base_radius * sin(params->base_angle[k]), 0};
    double b[3] = {params->platform_radius * cos(params->platform_angle[k]),
                   params->platform_radius * sin(params->platform_angle[k]), 0};
    if (params->geometry == 1) /* the joints as given (docs/geometry.md) */
        for (int i = 0; i < 3; ++i)
            a[i] = params->base_joint[3 * k + i], b[i] = params->platform_joint[3 * k + i];
    double d2 = 0;
    for (int i = 0; i < 3; ++i) {
        const double d = pose->q[i] + R[i][0] * b[0] + R[i][1] * b[1] + R[i][2] * b[2] - a[i];
        d2 += d * d;
    }
    return sqrt(d2);
}

stewart_inverse *test_inverse(const stewart_model *m) {
    stewart_inverse_options o;
    stewart_inverse_options_default(&o);
    return test_inverse_with(m, &o);
}

stewart_inverse *test_inverse_with(const stewart_model *m, const stewart_inverse_options *o) {
    char msg[STEWART_MESSAGE_SIZE];
    return made(stewart_inverse_create(m, o, msg, sizeof msg), msg);
}

stewart_forward *test_forward(const stewart_model *m) {
    stewart_forward_options o;
    stewart_forward_options_default(&o);
    char msg[STEWART_MESSAGE_SIZE];
    return made(stewart_forward_create(m, &o, msg, sizeof msg), msg);
}

stewart_plant_options test_plant_options(int fidelity) {
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    o.fidelity = fidelity;
    return o;
}

stewart_plant *test_plant_with(const stewart_model *m, const stewart_plant_options *o) {
    char msg[STEWART_MESSAGE_SIZE];
    return made(stewart_plant_create(m, o, msg, sizeof msg), msg);
}

stewart_status solve_as(stewart_inverse *d, const stewart_inverse_options *o,
                        const stewart_pose *pose, stewart_inverse_output *out) {
    char msg[STEWART_MESSAGE_SIZE];
    stewart_inverse *with_o = stewart_inverse_create(stewart_inverse_model(d), o, msg, sizeof msg);
    if (!with_o) {
        TEST_FAIL_MESSAGE(msg);
        return STEWART_ERR_MEMORY;
    }
    stewart_status s = stewart_inverse_copy(with_o, d);
    stewart_inverse_input in;
    in.pose = *pose;
    if (s == STEWART_OK) s = stewart_inverse_solve(with_o, &in, out);
    stewart_inverse_copy(d, with_o);
    stewart_inverse_free(with_o);
    return s;
}

stewart_inverse_output solve_ok(stewart_inverse *d, stewart_fidelity f, const stewart_pose *pose) {
    stewart_inverse_options o = test_options(f);
    stewart_inverse_output out;
    const stewart_status s = solve_as(d, &o, pose, &out);
    if (s != STEWART_OK) {
        char text[STEWART_MESSAGE_SIZE + 64];
        snprintf(text, sizeof text, "%s: %s", stewart_status_name(s), stewart_inverse_message(d));
        TEST_FAIL_MESSAGE(text);
    }
    return out;
}

uint64_t test_random(uint64_t *s) {
    *s ^= *s >> 12, *s ^= *s << 25, *s ^= *s >> 27;
    return *s * 2685821657736338717ULL;
}

double corrupted_value(uint64_t *rng, double v) {
    static const double specials[] = {
        0.0,      -0.0,    1.0,    -1.0, 0.5,      1e15,      -1e15, 1e300, DBL_MAX, -DBL_MAX,
        4.9e-324, DBL_MIN, 1e-300, NAN,  INFINITY, -INFINITY, 100.0, 3.0,   1e6};
    const uint64_t r = test_random(rng);
    switch (r % 6) {
        case 0: { /* one bit flipped */
            uint64_t bits;
            memcpy(&bits, &v, sizeof bits);
            bits ^= 1ULL << ((r >> 8) % 64);
            memcpy(&v, &bits, sizeof v);
            return v;
        }
        case 1: return specials[(r >> 8) % (sizeof specials / sizeof specials[0])];
        case 2: return v * (1 + 1e-6 * (double)((r >> 8) % 1000));
        case 3: return v + 2 * M_PI * (double)((int)((r >> 8) % 7) - 3);
        case 4: return -v;
        default: return ldexp((double)((r >> 8) % 2001) / 1000.0 - 1.0, (int)((r >> 20) % 80) - 40);
    }
}
