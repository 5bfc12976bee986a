#include "linearize_support.h"

#include <math.h>

#include "platform_fixture.h"
#include "test_support.h"
#include "unity.h"

stewart_linearize *linearize_make(int fidelity) {
    stewart_linearize_options o;
    stewart_linearize_options_default(&o);
    o.fidelity = fidelity;
    char message[STEWART_MESSAGE_SIZE];
    stewart_linearize *l = stewart_linearize_create(model, &o, message, sizeof message);
    TEST_ASSERT_NOT_NULL_MESSAGE(l, message);
    return l;
}

void block_add(block_error *e, double exact, double difference) {
    if (fabs(exact - difference) > e->error) e->error = fabs(exact - difference);
    if (fabs(exact) > e->scale) e->scale = fabs(exact);
}

double block_relative(block_error e, double value_scale, double h) {
    const double rounding = 16 * 2.220446049250313e-16 * value_scale / h;
    const double beyond = e.error > rounding ? e.error - rounding : 0;
    return beyond / (e.scale > 0 ? e.scale : 1);
}

double inverse_jacobian_error(const stewart_linearize_inverse_output *exact,
                              const stewart_pose *pose, int fidelity) {
    block_error blocks[6][3] = {{{0, 0}}};
    for (int j = 0; j < 18; ++j) {
        stewart_pose plus = *pose, minus = *pose;
        double *a = j < 6 ? plus.q : j < 12 ? plus.q_dot : plus.q_ddot;
        double *b = j < 6 ? minus.q : j < 12 ? minus.q_dot : minus.q_ddot;
        const double h = j < 12 ? LINEARIZE_STEP_STATE : LINEARIZE_STEP_ACCEL;
        a[j % 6] += h;
        b[j % 6] -= h;
        const stewart_inverse_output up = solve_ok(data, fidelity, &plus);
        const stewart_inverse_output down = solve_ok(data, fidelity, &minus);
        for (int k = 0; k < 6; ++k) {
            const double d[4] = {
                (up.lengths.length[k] - down.lengths.length[k]) / (2 * h),
                (up.lengths.length_rate[k] - down.lengths.length_rate[k]) / (2 * h),
                (up.lengths.length_accel[k] - down.lengths.length_accel[k]) / (2 * h),
                (up.force[k] - down.force[k]) / (2 * h)};
            for (int r = 0; r < 4; ++r)
                block_add(&blocks[r][j / 6], exact->jacobian[6 * r + k][j], d[r]);
        }
        for (int i = 0; i < 3; ++i) {
            block_add(&blocks[4][j / 6], exact->jacobian[24 + i][j],
                      (up.base_force[i] - down.base_force[i]) / (2 * h));
            block_add(&blocks[5][j / 6], exact->jacobian[27 + i][j],
                      (up.base_torque[i] - down.base_torque[i]) / (2 * h));
        }
    }
    double value_scale[6] = {0};
    for (int k = 0; k < 6; ++k) {
        value_scale[0] = fmax(value_scale[0], fabs(exact->lengths.length[k]));
        value_scale[1] = fmax(value_scale[1], fabs(exact->lengths.length_rate[k]));
        value_scale[2] = fmax(value_scale[2], fabs(exact->lengths.length_accel[k]));
        value_scale[3] = fmax(value_scale[3], fabs(exact->force[k]));
    }
    for (int i = 0; i < 3; ++i) {
        value_scale[4] = fmax(value_scale[4], fabs(exact->base_force[i]));
        value_scale[5] = fmax(value_scale[5], fabs(exact->base_torque[i]));
    }
    double worst = 0;
    for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 3; ++c) {
            const double e = block_relative(blocks[r][c], value_scale[r],
                                            c < 2 ? LINEARIZE_STEP_STATE : LINEARIZE_STEP_ACCEL);
            if (e > worst) worst = e;
        }
    return worst;
}
