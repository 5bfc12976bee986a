// The limits object's C API (stewart/stewart_limits.h): life cycle, the check, the axis ranges.
#include <cmath>
#include <new>

#include "limits/axis_ranges.hpp"
#include "kinematics/pose_names.hpp"
#include "limits/limit_check.hpp"
#include "model.hpp"
#include "stewart/stewart_limits.h"
#include "util/create.hpp"
#include "util/message.hpp"

using stewart::clear_message;
using stewart::set_message;

struct stewart_limits {
    const stewart_model *model;
    stewart_limits_options options;
    char message[STEWART_MESSAGE_SIZE];
    stewart::LimitConstants constants;
};

namespace {

// STEWART_ERR_ARGUMENT naming a NULL argument or the first non-finite pose component.
stewart_status check_call(stewart_limits *limits, const stewart_limits_input *input,
                          const void *output) {
    if (!input || !output)
        return set_message(limits->message, sizeof limits->message, STEWART_ERR_ARGUMENT,
                           "%s is NULL", input ? "output" : "input");
    for (int i = 0; i < 6; ++i)
        if (!std::isfinite(input->q[i]))
            return set_message(limits->message, sizeof limits->message, STEWART_ERR_ARGUMENT,
                               "pose %s is %g: every pose component must be finite",
                               stewart::kPoseNames[i], input->q[i]);
    return clear_message(limits->message, sizeof limits->message);
}

// check_call's, and STEWART_ERR_ARGUMENT naming a flag out of range or the first non-finite
// derivative or force the flags say are given.
stewart_status check_leg_data(stewart_limits *limits, const stewart_limits_input &in) {
    char *msg = limits->message;
    const size_t size = sizeof limits->message;
    if (in.derivatives < 0 || in.derivatives > 3)
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "derivatives = %d: it must be 0 (the pose alone), 1 (and q_dot), 2 "
                           "(and q_ddot) or 3 (and q_dddot)",
                           in.derivatives);
    if (in.has_force != 0 && in.has_force != 1)
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "has_force = %d: it must be 0 (no forces) or 1", in.has_force);
    static const char *const kSuffix[] = {"_dot", "_ddot", "_dddot"};
    const double *rows[] = {in.q_dot, in.q_ddot, in.q_dddot};
    for (int d = 0; d < in.derivatives; ++d)
        for (int i = 0; i < 6; ++i)
            if (!std::isfinite(rows[d][i]))
                return set_message(msg, size, STEWART_ERR_ARGUMENT,
                                   "pose %s%s is %g: every derivative given must be finite",
                                   stewart::kPoseNames[i], kSuffix[d], rows[d][i]);
    for (int k = 0; in.has_force && k < STEWART_LEGS; ++k)
        if (!std::isfinite(in.force[k]))
            return set_message(msg, size, STEWART_ERR_ARGUMENT,
                               "force[%d] is %g: every force given must be finite", k + 1,
                               in.force[k]);
    return STEWART_OK;
}

}  // namespace

extern "C" {

// stewart_limits_options_default and _check: table/options.cpp, from the option table.

stewart_limits *stewart_limits_create(const stewart_model *model,
                                      const stewart_limits_options *options, char *msg,
                                      size_t size) {
    stewart_limits *limits =
        stewart::new_object_for<stewart_limits>(model, options, stewart_limits_options_check,
                                                "limits object", msg, size);
    if (!limits) return nullptr;
    limits->message[0] = '\0';
    limits->constants =
        stewart::limit_constants(model->params, model->geometry, options->warn_condition);
    clear_message(msg, size);
    return limits;
}

void stewart_limits_free(stewart_limits *limits) { delete limits; }

const char *stewart_limits_message(const stewart_limits *limits) {
    return limits ? limits->message : "limits is NULL";
}

stewart_status stewart_limits_check(stewart_limits *limits, const stewart_limits_input *input,
                                    stewart_limits_output *output) {
    if (!limits) return STEWART_ERR_ARGUMENT;
    stewart_status s = check_call(limits, input, output);
    if (s == STEWART_OK) s = check_leg_data(limits, *input);
    if (s != STEWART_OK) return s;
    // Into a copy: an error leaves the output untouched.
    stewart_limits_output out;
    stewart::check_limits(limits->constants, input->q, out);
    s = stewart::check_leg_limits(limits->constants, *input, out, limits->message,
                                  sizeof limits->message);
    if (s == STEWART_OK) *output = out;
    return s;
}

stewart_status stewart_limits_ranges(stewart_limits *limits, const stewart_limits_input *input,
                                     stewart_axis_ranges *output) {
    if (!limits) return STEWART_ERR_ARGUMENT;
    const stewart_status s = check_call(limits, input, output);
    if (s != STEWART_OK) return s;
    stewart::axis_ranges(limits->constants, input->q, *output);
    return STEWART_OK;
}

const char *stewart_limit_class_name(int limit_class) {
    switch (limit_class) {
        case STEWART_LIMIT_NONE: return "none";
        case STEWART_LIMIT_STROKE: return "stroke";
        case STEWART_LIMIT_BASE_JOINT: return "base_joint";
        case STEWART_LIMIT_PLATFORM_JOINT: return "platform_joint";
        case STEWART_LIMIT_INTERFERENCE: return "interference";
        case STEWART_LIMIT_CONDITION: return "condition";
        case STEWART_LIMIT_AXIS: return "axis";
        case STEWART_LIMIT_LEG_SPEED: return "leg_speed";
        case STEWART_LIMIT_LEG_ACCEL: return "leg_accel";
        case STEWART_LIMIT_LEG_JERK: return "leg_jerk";
        case STEWART_LIMIT_LEG_FORCE: return "leg_force";
    }
    return "unknown";
}

}  // extern "C"
