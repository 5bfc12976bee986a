#include "test_support.h"

#include <math.h>
#include <stdio.h>

#include "unity.h"

stewart_model *test_model(const stewart_params *params) {
    char msg[STEWART_MESSAGE_SIZE];
    stewart_model *m = stewart_model_create(params, msg, sizeof msg);
    if (!m) TEST_FAIL_MESSAGE(msg);
    return m;
}

stewart_options test_options(stewart_fidelity fidelity) {
    stewart_options o;
    stewart_options_default(&o);
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
    if (component == 2)
        sinusoid(&p, 2, 0.5, 0.04, 5.0, 0.0, t);
    else
        sinusoid(&p, component, 0.0, M_PI / 18.0, 5.0, 0.0, t);
    return p;
}

stewart_output solve_ok(const stewart_model *m, stewart_data *d, stewart_fidelity f,
                        const stewart_pose *pose) {
    stewart_options o = test_options(f);
    stewart_output out;
    const stewart_status s = stewart_solve(m, d, &o, pose, &out);
    if (s != STEWART_OK) {
        char text[STEWART_MESSAGE_SIZE + 64];
        snprintf(text, sizeof text, "%s: %s", stewart_status_name(s), stewart_data_message(d));
        TEST_FAIL_MESSAGE(text);
    }
    return out;
}
