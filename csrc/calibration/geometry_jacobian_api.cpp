// stewart_geometry_jacobian (stewart_calibration.h): the model's geometry and frames into the
// closed forms of geometry_jacobian.cpp, the result into the C struct.
#include <cmath>

#include "kinematics/geometry_jacobian.hpp"
#include "model.hpp"
#include "stewart/stewart_calibration.h"
#include "util/message.hpp"

using stewart::set_message;

namespace {

// The geometry the readings depend on, from the model.
stewart::CalibrationGeometry calibration_geometry(const stewart_model &m) {
    stewart::CalibrationGeometry g;
    g.base_points = m.geometry.base_points;
    g.platform_points = m.geometry.platform_points;
    const stewart_params &p = m.params;
    for (int i = 0; i < 6; ++i) {
        g.length_offset[i] = p.length_offset[i];
        g.tool_frame[i] = p.tool_frame[i];
        g.user_frame[i] = p.user_frame[i];
    }
    g.min_length = m.geometry.min_length;
    return g;
}

}  // namespace

extern "C" stewart_status stewart_geometry_jacobian(const stewart_model *model,
                                                    const double pose[6],
                                                    stewart_geometry_jacobian_output *out,
                                                    char *msg, size_t size) {
    if (!model || !pose || !out)
        return set_message(msg, size, STEWART_ERR_ARGUMENT, "%s is NULL",
                           !model  ? "model"
                           : !pose ? "pose"
                                   : "out");
    for (int i = 0; i < 6; ++i)
        if (!std::isfinite(pose[i]))
            return set_message(msg, size, STEWART_ERR_ARGUMENT,
                               "pose input %s is %g: it must be finite", stewart::kPoseNames[i],
                               pose[i]);
    // The closed forms take the frames' angles and the poses as Rz Ry Rx in z-up frames.
    if (model->frames.rotation_order != stewart::kRotationZYX || model->frames.z_down)
        return set_message(msg, size, STEWART_ERR_UNSUPPORTED,
                           "the geometry Jacobian (calibration) takes rotation_order 0 and "
                           "frame_convention 0: give the platform in those (stewart.convert_angles "
                           "converts the poses and frames' angles)");
    stewart::GeometryJacobian J;
    const stewart_status s =
        stewart::geometry_jacobian(calibration_geometry(*model), pose, J, msg, size);
    if (s != STEWART_OK) return s;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        out->length[k] = J.length[k];
        out->reading[k] = J.reading[k];
        out->length_offset[k] = J.length_offset[k];
        for (int i = 0; i < 3; ++i) {
            out->base_joint[k][i] = J.base_joint(k, i);
            out->platform_joint[k][i] = J.platform_joint(k, i);
        }
        for (int i = 0; i < 6; ++i) {
            out->tool_frame[k][i] = J.tool_frame(k, i);
            out->user_frame[k][i] = J.user_frame(k, i);
            out->pose[k][i] = J.pose(k, i);
        }
    }
    return stewart::clear_message(msg, size);
}

extern "C" stewart_status stewart_model_joints(const stewart_model *model, double base_joint[18],
                                               double platform_joint[18]) {
    if (!model || !base_joint || !platform_joint) return STEWART_ERR_ARGUMENT;
    // In the frames the parameters are given in: z down turns y and z back.
    const double sign[3] = {1.0, model->frames.z_down ? -1.0 : 1.0,
                            model->frames.z_down ? -1.0 : 1.0};
    for (int k = 0; k < STEWART_LEGS; ++k)
        for (int i = 0; i < 3; ++i) {
            base_joint[3 * k + i] = sign[i] * model->geometry.base_points(i, k);
            platform_joint[3 * k + i] = sign[i] * model->geometry.platform_points(i, k);
        }
    return STEWART_OK;
}
