/*
 * Kinematic calibration's C call: at a measured pose, the six sensor readings the model predicts
 * and their closed-form derivatives with respect to the geometry (docs/calibration.md).
 *
 * The pose is that of the tool frame in the user frame (x, y, z, roll, pitch, yaw), as a laser
 * tracker measures it; the platform then sits at T_base_platform = T_user_frame · T_pose ·
 * T_tool_frame⁻¹, leg k's joint-to-joint length is L_k = |p + R b_k - a_k| and its sensor reads
 * L_k - length_offset_k. An identification (Python stewart.calibrate) stacks these rows over the
 * measured poses. The call keeps no history, so it has no solver object: like the model it reads,
 * it may be used from any number of threads at once.
 */
#ifndef STEWART_STEWART_CALIBRATION_H
#define STEWART_STEWART_CALIBRATION_H

#include "stewart/stewart.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Readings at one pose and their derivatives; row k is leg k+1's reading. A leg's reading
 * depends on its own two joints and offset only, so those blocks keep leg k's columns alone. */
typedef struct stewart_geometry_jacobian_output {
    double length[STEWART_LEGS];            /* joint-to-joint length L_k [m] */
    double reading[STEWART_LEGS];           /* L_k - length_offset_k: the sensor's reading [m] */
    double base_joint[STEWART_LEGS][3];     /* d reading_k / d base joint of leg k (x, y, z) */
    double platform_joint[STEWART_LEGS][3]; /* d reading_k / d platform joint of leg k */
    double length_offset[STEWART_LEGS];     /* d reading_k / d length_offset_k (-1) */
    double tool_frame[STEWART_LEGS][6];     /* d reading_k / d tool_frame (x, y, z [1], angles
                                                [m/rad]) */
    double user_frame[STEWART_LEGS][6];     /* d reading_k / d user_frame */
    double pose[STEWART_LEGS][6];           /* d reading_k / d pose: the inverse Jacobian in the
                                                user frame, per angle rate */
} stewart_geometry_jacobian_output;

/* The readings at pose (6 values) and their derivatives. STEWART_OK and out written whole; else
 * out untouched and message naming the variable and its value: STEWART_ERR_ARGUMENT for a NULL
 * argument or a non-finite pose component, STEWART_ERR_UNREACHABLE for a leg of zero length,
 * STEWART_ERR_UNSUPPORTED for a model with rotation_order or frame_convention 1. */
stewart_status stewart_geometry_jacobian(const stewart_model *model, const double pose[6],
                                         stewart_geometry_jacobian_output *out, char *message,
                                         size_t size);

/* The joint centres the model uses, whichever parameters gave them (the circles of geometry 0 or
 * the coordinates of geometry 1): base_joint in the base frame, platform_joint in the platform
 * frame (both z down when frame_convention is 1), x1, y1, z1, ..., z6 [m]. STEWART_ERR_ARGUMENT
 * if an argument is NULL. */
stewart_status stewart_model_joints(const stewart_model *model, double base_joint[18],
                                    double platform_joint[18]);

#ifdef __cplusplus
}
#endif

#endif /* STEWART_STEWART_CALIBRATION_H */
