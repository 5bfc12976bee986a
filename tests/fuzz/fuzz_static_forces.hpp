// The inverse side's actuator forces at rest at home (default parameters, full fidelity), for the
// plant fuzz targets (co-simulation and Model Exchange): the plant moves slowly near them, where
// most of its code runs.
#ifndef STEWART_FUZZ_STATIC_FORCES_HPP
#define STEWART_FUZZ_STATIC_FORCES_HPP

#include <cstdlib>
#include <cstring>

#include "stewart/stewart.h"

namespace {

double static_forces[6];

// Fills static_forces once (aborts if the inverse model cannot hold the platform at home).
void compute_static_forces() {
    static bool done = false;
    if (done) return;
    done = true;
    stewart_params p;
    stewart_params_default(&p);
    stewart_model *model = stewart_model_create(&p, nullptr, 0);
    stewart_inverse_options o;
    stewart_inverse_options_default(&o);
    o.fidelity = STEWART_FULL;
    stewart_inverse *data = stewart_inverse_create(model, &o, nullptr, 0);
    const stewart_inverse_input home = {{{0, 0, p.home_height, 0, 0, 0}, {0}, {0}}};
    stewart_inverse_output out;
    if (!model || !data || stewart_inverse_solve(data, &home, &out) != STEWART_OK) std::abort();
    std::memcpy(static_forces, out.force, sizeof static_forces);
    stewart_inverse_free(data);
    stewart_model_free(model);
}

}  // namespace

#endif
