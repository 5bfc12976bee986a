// The C API of the model: made once from the parameters, read-only afterwards, shared by the
// solver objects of every direction.
#include <new>

#include "model.hpp"
#include "util/message.hpp"

using stewart::clear_message;
using stewart::set_message;

extern "C" stewart_model *stewart_model_create(const stewart_params *params, char *msg,
                                               size_t size) {
    if (stewart_params_check(params, msg, size) != STEWART_OK) return nullptr;
    stewart_model *m = new (std::nothrow) stewart_model;
    if (!m) {
        set_message(msg, size, STEWART_ERR_MEMORY, "out of memory creating the model");
        return nullptr;
    }
    m->given = *params;
    m->params = stewart::params_in_solver_frames(*params);
    params = &m->params;
    m->geometry = stewart::platform_geometry(*params);
    m->platform = stewart::lumped_platform(*params);
    m->gravity = Eigen::Vector3d(params->gravity);
    m->frames = stewart::frames_of(*params);
    m->length_offsets = false;
    for (double offset : params->length_offset)
        m->length_offsets = m->length_offsets || offset != 0;
    for (int k = 0; k < STEWART_LEGS; ++k) m->drive[k] = stewart::leg_drive(*params, k);
    m->drives = stewart::has_drives(*params);
    m->full = stewart::build_full_platform(*params, stewart::FullDrive::ActuatorLengths,
                                           m->full_layout, msg, size);
    if (!m->full) {
        delete m;
        return nullptr;
    }
    // A model singular at home has no forward kinematics (stewart_forward_create says so); the
    // other directions still work.
    stewart::forward_constants(m->geometry, *params, m->forward, msg, size);
    clear_message(msg, size);
    return m;
}

extern "C" void stewart_model_free(stewart_model *m) { delete m; }

extern "C" const stewart_params *stewart_model_params(const stewart_model *m) {
    return m ? &m->given : nullptr;
}

extern "C" void stewart_model_reflected_mass(const stewart_model *m, double mass[STEWART_LEGS]) {
    if (!m || !mass) return;
    for (int k = 0; k < STEWART_LEGS; ++k) mass[k] = stewart::reflected_mass(m->drive[k]);
}

extern "C" const char *stewart_status_name(stewart_status s) {
    switch (s) {
        case STEWART_OK: return "ok";
        case STEWART_ERR_ARGUMENT: return "invalid argument";
        case STEWART_ERR_PARAMETER: return "invalid parameter";
        case STEWART_ERR_SINGULAR: return "singular";
        case STEWART_ERR_UNREACHABLE: return "unreachable pose";
        case STEWART_ERR_NOT_CONVERGED: return "not converged";
        case STEWART_ERR_UNSUPPORTED: return "unsupported";
        case STEWART_ERR_MEMORY: return "out of memory";
        case STEWART_ERR_OTHER_BRANCH: return "other assembly mode";
    }
    return "unknown status";
}
