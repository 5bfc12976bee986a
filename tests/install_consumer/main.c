/* Solves the home pose at every fidelity level through the installed headers and libraries, and
 * builds a pendulum on the installed core. */
#include <stdio.h>

#include "mbs/mbs.h"
#include "stewart/stewart.h"
#include "stewart/stewart_full.h"

int main(void) {
    stewart_params params;
    stewart_params_default(&params);
    char msg[STEWART_MESSAGE_SIZE];
    stewart_model *model = stewart_model_create(&params, msg, sizeof msg);
    if (!model) {
        fprintf(stderr, "model: %s\n", msg);
        return 1;
    }
    const stewart_inverse_input home = {{{0, 0, 0.5, 0, 0, 0}, {0}, {0}}};
    stewart_inverse_options options;
    stewart_inverse_options_default(&options);
    double force[3];
    for (int f = STEWART_KINEMATIC; f <= STEWART_FULL; ++f) {
        options.fidelity = (stewart_fidelity)f;
        stewart_inverse *inverse = stewart_inverse_create(model, &options, msg, sizeof msg);
        if (!inverse) {
            fprintf(stderr, "fidelity %d: %s\n", f, msg);
            return 1;
        }
        stewart_inverse_output out;
        stewart_status s = stewart_inverse_solve(inverse, &home, &out);
        if (s != STEWART_OK) {
            fprintf(stderr, "fidelity %d: %s\n", f, stewart_inverse_message(inverse));
            return 1;
        }
        stewart_inverse_free(inverse);
        force[f] = out.force[0];
        printf("fidelity %d: L1 = %.6f m, F1 = %.4f N\n", f, out.lengths.length[0], out.force[0]);
    }
    /* the core alone: a pendulum (a body on a revolute joint to a fixed ground) */
    mbs_model *crank = mbs_model_create();
    const double none[3] = {0, 0, 0}, rod[3] = {0, 1.0 / 12, 1.0 / 12};
    const double ground_q[7] = {0, 0, 0, 1, 0, 0, 0}, bar_q[7] = {0.5, 0, 0, 1, 0, 0, 0};
    const double origin[3] = {0, 0, 0}, end[3] = {-0.5, 0, 0}, ez[3] = {0, 0, 1};
    const int ground = mbs_add_body(crank, "ground", 0, none, ground_q);
    const int bar = mbs_add_body(crank, "bar", 1, rod, bar_q);
    const int pivot = mbs_add_revolute(crank, ground, origin, ez, bar, end, ez);
    if (mbs_fix_body(crank, ground) != MBS_OK || mbs_add_angle_driver(crank, pivot, NULL) < 0 ||
        mbs_model_finalize(crank, msg, sizeof msg) != MBS_OK) {
        fprintf(stderr, "pendulum: %s %s\n", msg, mbs_model_message(crank));
        return 1;
    }
    mbs_model_free(crank);
    stewart_model_free(model);
    /* Legs have mass at the full level: they carry a little more than the massless level. */
    return (force[0] == 0 && force[2] > force[1] && force[1] > 0) ? 0 : 1;
}
