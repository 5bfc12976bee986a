// The thesis' force formulation (thesis_forces.h): a test oracle, not part of the library's API.
#include "thesis_forces.h"

#include <cmath>
#include <memory>

#include "inverse/full_model.hpp"
#include "kinematics/closed_form.hpp"
#include "util/message.hpp"

extern "C" stewart_status stewart_thesis_forces(const stewart_params *p, const stewart_pose *pose,
                                                double force[STEWART_LEGS], char *msg,
                                                size_t size) {
    using namespace stewart;
    if (!p || !pose || !force) return set_message(msg, size, STEWART_ERR_ARGUMENT, "NULL argument");
    stewart_status s = stewart_params_check(p, msg, size);
    if (s != STEWART_OK) return s;
    if ((s = check_pose(*pose, msg, size)) != STEWART_OK) return s;
    // The pose checks of stewart_inverse_solve (default options) before anything is built: at a
    // singular leg Jacobian the 6 x 6 solve below would return forces of any size.
    stewart_inverse_options o;
    stewart_inverse_options_default(&o);
    const PlatformGeometry geometry = platform_geometry(*p);
    const Motion motion = motion_of_pose(*pose);
    LegKinematics legs;
    if ((s = leg_kinematics(geometry, motion, legs, msg, size)) != STEWART_OK) return s;
    LegJacobian jacobian;
    leg_jacobian(geometry, legs, jacobian);
    if ((s = check_condition(jacobian.condition, o.singular_condition, msg, size)) != STEWART_OK)
        return s;

    FullLayout layout;
    std::unique_ptr<mbs_model> model =
        build_full_platform(*p, FullDrive::PlatformPose, layout, msg, size);
    if (!model) return STEWART_ERR_PARAMETER;
    mbs_data data(model.get(), mbs::SolverOptions());
    if (!data.state.ok())
        return set_message(msg, size, STEWART_ERR_MEMORY, "%s", data.state.message);
    stewart_inverse_output out{};
    if ((s = full_solve(layout, data.state, o, motion, legs, out, msg, size)) != STEWART_OK)
        return s;
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (!std::isfinite(out.force[k]))
            return set_message(msg, size, STEWART_ERR_ARGUMENT,
                               "the pose inputs are out of range: force F%d = %g is not finite "
                               "(x = %g, y = %g, z = %g m)",
                               k + 1, out.force[k], pose->q[0], pose->q[1], pose->q[2]);
    for (int k = 0; k < STEWART_LEGS; ++k) force[k] = out.force[k];
    return clear_message(msg, size);
}
