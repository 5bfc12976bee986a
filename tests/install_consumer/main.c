/* Solves the home pose at every fidelity level through the installed headers and library. */
#include <stdio.h>

#include "stewart/slider_crank.h"
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
    stewart_data *data = stewart_data_create(model);
    stewart_pose home = {{0, 0, 0.5, 0, 0, 0}, {0}, {0}};
    stewart_options options;
    stewart_options_default(&options);
    double force[3];
    for (int f = STEWART_KINEMATIC; f <= STEWART_FULL; ++f) {
        stewart_output out;
        options.fidelity = (stewart_fidelity)f;
        stewart_status s = stewart_solve(model, data, &options, &home, &out);
        if (s != STEWART_OK) {
            fprintf(stderr, "fidelity %d: %s\n", f, stewart_data_message(data));
            return 1;
        }
        force[f] = out.force[0];
        printf("fidelity %d: L1 = %.6f m, F1 = %.4f N\n", f, out.length[0], out.force[0]);
    }
    slider_crank_params sc;
    slider_crank_layout layout;
    slider_crank_params_default(&sc);
    mbs_model *crank = slider_crank_create(&sc, &layout, msg, sizeof msg);
    if (!crank) {
        fprintf(stderr, "slider-crank: %s\n", msg);
        return 1;
    }
    mbs_model_free(crank);
    stewart_data_free(data);
    stewart_model_free(model);
    /* Legs have mass at the full level: they carry a little more than the massless level. */
    return (force[0] == 0 && force[2] > force[1] && force[1] > 0) ? 0 : 1;
}
