// slider-crank-solve: the thesis' slider-crank (4.1) on the multibody core, the crank driven at a
// constant speed; writes positions, velocities, accelerations and the driving torque per sample.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "slider_crank.h"

namespace {

int usage(FILE *to) {
    std::fprintf(to, "usage: slider-crank-solve [--rpm 10] [--turns 2] [--dt 0.01] OUT.csv\n"
                     "  OUT.csv: t,crank_angle,slider_x,slider_v,slider_a,crank_torque,iterations,"
                     "residual [SI units]\n");
    return to == stderr ? 2 : 0;
}

bool parse_positive(const char *text, double &value) {
    char *end = nullptr;
    value = std::strtod(text, &end);
    return *end == '\0' && std::isfinite(value) && value > 0;
}

}  // namespace

int main(int argc, char **argv) {
    double rpm = 10, turns = 2, dt = 0.01;
    const char *out_path = nullptr;
    for (int i = 1; i < argc; ++i) {
        double *target = !std::strcmp(argv[i], "--rpm")     ? &rpm
                         : !std::strcmp(argv[i], "--turns") ? &turns
                         : !std::strcmp(argv[i], "--dt")    ? &dt
                                                            : nullptr;
        if (!std::strcmp(argv[i], "--help")) return usage(stdout);
        if (target) {
            if (i + 1 >= argc || !parse_positive(argv[++i], *target)) {
                std::fprintf(stderr, "slider-crank-solve: %s needs a positive number\n",
                             argv[i - 1]);
                return 2;
            }
        } else if (argv[i][0] == '-' || out_path) {
            return usage(stderr);
        } else {
            out_path = argv[i];
        }
    }
    if (!out_path) return usage(stderr);

    slider_crank_params params;
    slider_crank_params_default(&params);
    slider_crank_layout layout;
    char message[MBS_MESSAGE_SIZE];
    mbs_model *model = slider_crank_create(&params, &layout, message, sizeof message);
    if (!model) {
        std::fprintf(stderr, "slider-crank-solve: %s\n", message);
        return 1;
    }
    mbs_data *data = mbs_data_create(model, MBS_LINEAR_AUTOMATIC);
    FILE *out = data ? std::fopen(out_path, "w") : nullptr;
    if (!out) {
        std::fprintf(stderr, "slider-crank-solve: cannot write %s\n", out_path);
        mbs_data_free(data);
        mbs_model_free(model);
        return 1;
    }
    mbs_options options;
    mbs_options_default(&options);
    const double omega = rpm * 2 * M_PI / 60;
    const double duration = turns * 2 * M_PI / omega;
    const long samples = std::lround(duration / dt);
    const int slider = MBS_BODY_R(layout.slider);
    const int torque_row = mbs_joint_first_row(model, layout.crank_driver_joint);
    std::fprintf(out, "t,crank_angle,slider_x,slider_v,slider_a,crank_torque,iterations,residual,"
                      "energy,bearing_force_x,bearing_force_y\n");
    int status = 0;
    for (long j = 0; j <= samples; ++j) {
        const double t = j * dt;
        mbs_set_driver(data, layout.crank_driver, omega * t, omega, 0.0);
        if (mbs_step(data, t, &options) != MBS_OK) {
            std::fprintf(stderr, "slider-crank-solve: t = %g: %s\n", t, mbs_data_message(data));
            status = 1;
            break;
        }
        // What the crank bearing puts on the ground (the frame's shaking force), and the energy
        // (its rate is the drive's power, crank_torque * omega).
        double bearing[3], bearing_torque[3];
        mbs_joint_reaction(data, layout.crank_bearing, 0, bearing, bearing_torque);
        std::fprintf(out, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%.3g,%.17g,%.17g,%.17g\n", t,
                     omega * t, mbs_q(data)[slider], mbs_q_dot(data)[slider],
                     mbs_q_ddot(data)[slider], mbs_lambda(data)[torque_row], mbs_iterations(data),
                     mbs_residual(data), mbs_energy(data, mbs_q(data), mbs_q_dot(data)), bearing[0],
                     bearing[1]);
    }
    std::fclose(out);
    mbs_data_free(data);
    mbs_model_free(model);
    return status;
}
