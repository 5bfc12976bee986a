// What the plant fuzz targets share (fuzz_plant_fmu.cpp: co-simulation, fuzz_plant_me_fmu.cpp:
// Model Exchange): the inverse side's actuator forces at rest at home (default parameters, full
// fidelity), near which the plant moves slowly and most of its code runs, and the output check.
#ifndef STEWART_FUZZ_PLANT_UNIT_HPP
#define STEWART_FUZZ_PLANT_UNIT_HPP

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "fuzz_fmu_unit.hpp"
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

// Every Real output read back with OK is finite; status is 0, 1 or 3. Keeps the Reals if asked.
void check_outputs(Unit &u, std::vector<double> *keep = nullptr) {
    check_real_outputs(u, 1u << 0 | 1u << 1 | 1u << 3, keep);
}

// All six forces near the static ones: relative offsets of up to 12.7 % (six int8 of the input).
void set_forces_near_statics(Unit &u, Reader &in) {
    const unsigned vrs[6] = {VR_F_1, VR_F_2, VR_F_3, VR_F_4, VR_F_5, VR_F_6};
    double f[6];
    for (int k = 0; k < 6; ++k) {
        int8_t offset = 0;
        in.take(&offset, 1);
        f[k] = static_forces[k] * (1 + offset / 1000.0);
    }
    u.set_real(vrs, 6, f);
}

// The operations both plant targets' inputs have: 1 SetReal of one force, any value (scaled:
// the specials are small), 13 all six forces near the static ones. False for any other op.
bool plant_operation(int op, Unit &u, Reader &in) {
    if (op == 1) {
        const unsigned vr = VR_F_1 + in.byte() % 6;
        const double v = 1e3 * in.value();
        u.set_real(&vr, 1, &v);
        return true;
    }
    if (op == 13) {
        set_forces_near_statics(u, in);
        return true;
    }
    return false;
}

}  // namespace

#endif
