// Forward kinematics of one row on its own (stewart_forward_solve_cold): a cold start from home,
// and when that lands on another assembly mode, a walk in length space from home's readings.
#include <cstring>

#include "forward/forward_object.hpp"
#include "model.hpp"
#include "stewart/stewart_forward.h"

namespace {

// The sensors' readings at the home pose: joint-to-joint lengths less the length offsets.
void home_readings(const stewart_model &m, double reading[6]) {
    const Eigen::Vector3d up(0.0, 0.0, m.params.home_height);
    for (int k = 0; k < 6; ++k)
        reading[k] =
            (m.geometry.platform_points.col(k) + up - m.geometry.base_points.col(k)).norm() -
            m.params.length_offset[k];
}

// Walks the lengths from home's readings to input's in `steps` equal steps, each solve tracking
// the one before; the last step is input itself (its derivatives too).
stewart_status walk_from_home(stewart_forward *d, const stewart_forward_input &input,
                              const double home[6], int steps, stewart_forward_output &out) {
    stewart_forward_reset(d);
    stewart_forward_input step{};
    step.time = input.time;  // no predictor: every step at the same time
    stewart_status s = STEWART_OK;
    for (int i = 1; i < steps && s == STEWART_OK; ++i) {
        const double f = static_cast<double>(i) / steps;
        for (int k = 0; k < 6; ++k)
            step.lengths.length[k] = home[k] + f * (input.lengths.length[k] - home[k]);
        s = stewart_forward_solve(d, &step, &out);
    }
    if (s != STEWART_OK) return s;
    stewart_forward_input last = input;
    last.use_guess = 0;
    return stewart_forward_solve(d, &last, &out);
}

}  // namespace

extern "C" stewart_status stewart_forward_solve_cold(stewart_forward *d,
                                                     const stewart_forward_input *input,
                                                     stewart_forward_output *output) {
    if (!d) return STEWART_ERR_ARGUMENT;
    if (!input || !output) return stewart_forward_solve(d, input, output);  // says which
    stewart_forward_reset(d);
    stewart_status s = stewart_forward_solve(d, input, output);
    if (s != STEWART_ERR_OTHER_BRANCH || input->use_guess) return s;
    double home[6];
    home_readings(*d->model, home);
    const stewart_forward_output from_home = *output;
    for (int steps : {8, 64}) {
        stewart_forward_output walked{};
        if (walk_from_home(d, *input, home, steps, walked) == STEWART_OK) {
            *output = walked;
            return STEWART_OK;
        }
    }
    // No walk reached it: the answer from home, refused as it was, and no history.
    stewart_forward_reset(d);
    *output = from_home;
    return stewart_forward_solve(d, input, output);
}
