// stewart_full.h: the full level's mechanism and the thesis' force formulation.
#include "stewart/stewart_full.h"

#include "model.hpp"
#include "util/message.hpp"

extern "C" const mbs_model *stewart_model_mechanism(const stewart_model *m) {
    return m ? m->full.get() : nullptr;
}

extern "C" const mbs_data *stewart_data_mechanism(const stewart_data *d) {
    return d ? d->full.get() : nullptr;
}

extern "C" stewart_status stewart_thesis_forces(const stewart_params *p, const stewart_pose *pose,
                                                double force[STEWART_LEGS], char *msg,
                                                size_t size) {
    using namespace stewart;
    if (!p || !pose || !force) return set_message(msg, size, STEWART_ERR_ARGUMENT, "NULL argument");
    stewart_status s = stewart_params_check(p, msg, size);
    if (s != STEWART_OK) return s;
    FullLayout layout;
    std::unique_ptr<mbs_model> model = build_full_platform(*p, FullDrive::PlatformPose, layout, msg, size);
    if (!model) return STEWART_ERR_PARAMETER;
    mbs_data data(model.get(), mbs::SolverOptions());
    if (!data.state.ok()) return set_message(msg, size, STEWART_ERR_MEMORY, "%s", data.state.message);
    const RigidMotion motion = rigid_motion(*pose);
    LegKinematics legs;
    if ((s = leg_kinematics(platform_geometry(*p), motion, legs, msg, size)) != STEWART_OK) return s;
    stewart_options o;
    stewart_options_default(&o);
    stewart_output out{};
    if ((s = full_solve(layout, data.state, o, motion, legs, out, msg, size)) != STEWART_OK) return s;
    for (int k = 0; k < STEWART_LEGS; ++k) force[k] = out.force[k];
    return clear_message(msg, size);
}
