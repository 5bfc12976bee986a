// The slider-crank builder: nothing but bodies and joints through the mbs C API.
#include "slider_crank.h"

#include <cmath>
#include <cstdio>

extern "C" void slider_crank_params_default(slider_crank_params *p) {
    if (!p) return;
    p->crank_length = 1.0;
    p->rod_length = 2.0;
    p->crank_mass = 1.0;
    p->rod_mass = 2.0;
    p->slider_mass = 3.0;
    p->gravity = 9.81;
}

extern "C" mbs_model *slider_crank_create(const slider_crank_params *p, slider_crank_layout *l,
                                          char *msg, size_t size) {
    if (!p || !l) {
        if (msg && size) std::snprintf(msg, size, "NULL argument");
        return nullptr;
    }
    if (!(p->crank_length > 0 && p->rod_length > p->crank_length)) {
        if (msg && size)
            std::snprintf(msg, size,
                          "crank_length = %.17g, rod_length = %.17g: need 0 < crank < rod",
                          p->crank_length, p->rod_length);
        return nullptr;
    }
    const double r = p->crank_length, L = p->rod_length;
    mbs_model *m = mbs_model_create();
    if (!m) return nullptr;
    const double g[3] = {0, -p->gravity, 0};
    mbs_set_gravity(m, g);
    // Slender rods along their local x: I = m l^2 / 12 about y and z, none about x.
    const double none[3] = {0, 0, 0};
    const double crank_I[3] = {0, p->crank_mass * r * r / 12, p->crank_mass * r * r / 12};
    const double rod_I[3] = {0, p->rod_mass * L * L / 12, p->rod_mass * L * L / 12};
    const double at_origin[7] = {0, 0, 0, 1, 0, 0, 0};
    const double crank_q[7] = {r / 2, 0, 0, 1, 0, 0, 0};
    const double rod_q[7] = {r + L / 2, 0, 0, 1, 0, 0, 0};
    const double slider_q[7] = {r + L, 0, 0, 1, 0, 0, 0};
    l->ground = mbs_add_body(m, "ground", 0.0, none, at_origin);
    l->crank = mbs_add_body(m, "crank", p->crank_mass, crank_I, crank_q);
    l->rod = mbs_add_body(m, "rod", p->rod_mass, rod_I, rod_q);
    l->slider = mbs_add_body(m, "slider", p->slider_mass, none, slider_q);

    const double origin[3] = {0, 0, 0}, ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0}, ez[3] = {0, 0, 1};
    const double crank_root[3] = {-r / 2, 0, 0}, crank_pin[3] = {r / 2, 0, 0};
    const double rod_start[3] = {-L / 2, 0, 0}, rod_end[3] = {L / 2, 0, 0};
    l->crank_bearing = mbs_add_revolute(m, l->ground, origin, ez, l->crank, crank_root, ez);
    const int ok =
        mbs_fix_body(m, l->ground) == MBS_OK && l->crank_bearing >= 0 &&
        mbs_add_spherical(m, l->crank, crank_pin, l->rod, rod_start) >= 0 &&
        (l->rod_slider_cardan = mbs_add_cardan(m, l->rod, rod_end, ey, l->slider, origin, ez)) >=
            0 &&
        (l->slider_guide = mbs_add_prismatic(m, l->ground, origin, ex, l->slider, origin, ex)) >=
            0 &&
        (l->crank_driver_joint = mbs_add_angle_driver(m, l->crank_bearing, &l->crank_driver)) >= 0;
    if (!ok) {
        if (msg && size) std::snprintf(msg, size, "slider-crank: %s", mbs_model_message(m));
        mbs_model_free(m);
        return nullptr;
    }
    if (mbs_model_finalize(m, msg, size) != MBS_OK) {
        mbs_model_free(m);
        return nullptr;
    }
    return m;
}
