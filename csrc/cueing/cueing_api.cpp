// The cueing unit's C API (stewart/stewart_cueing.h): life cycle, state bytes, the step.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <new>

#include "cueing/classical.hpp"
#include "cueing/leg_limiter.hpp"
#include "cueing/limiter.hpp"
#include "model.hpp"
#include "stewart/stewart_cueing.h"
#include "stewart/stewart_limits.h"
#include "stewart/stewart_table.h"
#include "util/create.hpp"
#include "util/message.hpp"

using stewart::clear_message;
using stewart::set_message;

namespace {

// What a cueing object carries from one sample to the next: all of it plain numbers.
struct CueingState {
    stewart::cueing::ClassicalState classical;
    double scale, scale_rate;          // the limiter's s and s' at the last sample
    stewart::cueing::LegState output;  // the output's motion (the leg limiter's), from home
};

// The saved bytes: a tag, the options they were made with, the state.
constexpr std::uint32_t kStateTag = 0x43554532;  // "CUE2"
struct SavedState {
    std::uint32_t tag;
    stewart_cueing_options options;
    CueingState state;
};

void rest(CueingState &s) {
    std::memset(&s, 0, sizeof s);
    s.scale = 1.0;
}

bool finite_state(const CueingState &s) {
    const double *v = reinterpret_cast<const double *>(&s.classical);
    for (size_t i = 0; i < sizeof s.classical / sizeof(double); ++i)
        if (!std::isfinite(v[i])) return false;
    const double *w = reinterpret_cast<const double *>(&s.output);
    for (size_t i = 0; i < sizeof s.output / sizeof(double); ++i)
        if (!std::isfinite(w[i])) return false;
    return s.scale >= 0.0 && s.scale <= 1.0 && std::isfinite(s.scale_rate);
}

}  // namespace

struct stewart_cueing {
    const stewart_model *model;
    stewart_cueing_options options;
    mutable char message[STEWART_MESSAGE_SIZE];
    stewart::cueing::ClassicalDesign design;
    stewart::cueing::ClassicalSteps steps;  // the filters discretised for the last dt
    stewart::cueing::Limiter limiter;
    stewart::cueing::LegLimiter leg_limiter;  // the legs' speed and acceleration limits
    stewart_limits *limits;
    stewart_inverse *legs;  // the legs' rates and forces, when a leg motion limit is given
    int leg_limits_given;   // STEWART_CUEING_LEG_* bits of the limits given
    CueingState state;
};

namespace {

// The STEWART_CUEING_LEG_* bits of the leg motion limits p gives (a limit of 0 is none).
int leg_limits_given(const stewart_params &p) {
    int bits = 0;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        if (p.leg_speed_max[k] > 0) bits |= STEWART_CUEING_LEG_SPEED;
        if (p.leg_accel_max[k] > 0) bits |= STEWART_CUEING_LEG_ACCEL;
        if (p.leg_force_max[k] > 0) bits |= STEWART_CUEING_LEG_FORCE;
    }
    return bits;
}

// The leg motion limits the pose breaks (STEWART_CUEING_LEG_* bits): the inverse solver's leg
// rates and accelerations (and massless forces when a force limit is given) against them; every
// given bit when the pose cannot be solved, since nothing then vouches for the legs.
int broken_leg_limits(stewart_cueing &c, const stewart_pose &pose) {
    if (!c.legs) return 0;
    stewart_inverse_input in;
    in.pose = pose;
    stewart_inverse_output out;
    if (stewart_inverse_solve(c.legs, &in, &out) != STEWART_OK) return c.leg_limits_given;
    const stewart_params &p = c.model->params;
    int bits = 0;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        if (p.leg_speed_max[k] > 0 && std::fabs(out.lengths.length_rate[k]) > p.leg_speed_max[k])
            bits |= STEWART_CUEING_LEG_SPEED;
        if (p.leg_accel_max[k] > 0 && std::fabs(out.lengths.length_accel[k]) > p.leg_accel_max[k])
            bits |= STEWART_CUEING_LEG_ACCEL;
        if (p.leg_force_max[k] > 0 && std::fabs(out.force[k]) > p.leg_force_max[k])
            bits |= STEWART_CUEING_LEG_FORCE;
    }
    return bits;
}

// The inverse solver for the leg limits given (massless when a force limit is, else kinematic),
// or NULL when none is given; false if it cannot be made (message says why).
bool make_leg_solver(stewart_cueing &c, char *msg, size_t size) {
    c.leg_limiter = stewart::cueing::leg_limiter(c.limiter, c.model->geometry, c.model->params);
    c.leg_limits_given = leg_limits_given(c.model->params);
    c.legs = nullptr;
    if (!c.leg_limits_given) return true;
    stewart_inverse_options io;
    stewart_inverse_options_default(&io);
    io.fidelity =
        (c.leg_limits_given & STEWART_CUEING_LEG_FORCE) ? STEWART_MASSLESS : STEWART_KINEMATIC;
    io.warn_condition = io.singular_condition =
        std::fmax(c.options.warn_condition, io.warn_condition);
    c.legs = stewart_inverse_create(c.model, &io, msg, size);
    return c.legs != nullptr;
}

// The home pose within every limit, else a message naming the first limit it fails.
bool home_within(stewart_cueing &c, char *msg, size_t size) {
    const double none[6] = {0, 0, 0, 0, 0, 0};
    if (stewart::cueing::within(c.limiter, none, 0.0)) return true;
    stewart_limits_input in{};
    stewart_pose platform{}, caller{};
    for (int i = 0; i < 6; ++i) platform.q[i] = c.limiter.home[i];
    stewart::cueing::caller_pose(c.limiter, platform, 0, caller);
    std::memcpy(in.q, caller.q, sizeof in.q);
    stewart_limits_output out{};
    stewart_limits_check(c.limits, &in, &out);
    set_message(msg, size, STEWART_ERR_PARAMETER,
                "the home pose is beyond the %s limit: the cueing unit moves about home and needs "
                "it within every limit (check the platform with stewart-solve --check)",
                stewart_limit_class_name(out.first));
    return false;
}

stewart_status check_input(stewart_cueing *c, const stewart_cueing_input *in, const void *out) {
    if (!in || !out)
        return set_message(c->message, sizeof c->message, STEWART_ERR_ARGUMENT, "%s is NULL",
                           in ? "output" : "input");
    if (!(std::isfinite(in->dt) && in->dt >= 0.0))
        return set_message(c->message, sizeof c->message, STEWART_ERR_ARGUMENT,
                           "dt = %g must be finite and >= 0 [s]", in->dt);
    static const char *const kAxes[3] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(in->specific_force[i]))
            return set_message(c->message, sizeof c->message, STEWART_ERR_ARGUMENT,
                               "specific_force %s is %g: every input must be finite", kAxes[i],
                               in->specific_force[i]);
        if (!std::isfinite(in->angular_velocity[i]))
            return set_message(c->message, sizeof c->message, STEWART_ERR_ARGUMENT,
                               "angular_velocity %s is %g: every input must be finite", kAxes[i],
                               in->angular_velocity[i]);
    }
    return clear_message(c->message, sizeof c->message);
}

}  // namespace

extern "C" {

// stewart_cueing_options_default and _check: table/options.cpp, from the option table.

stewart_cueing *stewart_cueing_create(const stewart_model *model,
                                      const stewart_cueing_options *options, char *msg,
                                      size_t size) {
    if (!stewart::create_arguments_ok(model, options, stewart_cueing_options_check, msg, size))
        return nullptr;
    const double g = model->gravity.norm();
    if (!(g > 0.0)) {
        set_message(msg, size, STEWART_ERR_PARAMETER,
                    "gravity is 0: the cueing unit needs it for the vehicle's rest specific force "
                    "and the tilt coordination");
        return nullptr;
    }
    stewart_limits_options lo;
    stewart_limits_options_default(&lo);
    lo.warn_condition = options->warn_condition;
    stewart_limits *limits = stewart_limits_create(model, &lo, msg, size);
    if (!limits) return nullptr;
    stewart_cueing *c = stewart::new_object<stewart_cueing>("cueing object", msg, size);
    if (!c) {
        stewart_limits_free(limits);
        return nullptr;
    }
    c->model = model;
    // Field by field over zeroed bytes: copy and load compare the options as bytes, and the
    // caller's struct may hold anything in its padding.
    std::memset(&c->options, 0, sizeof c->options);
#define COPY_OPTION(id, name, ...) c->options.name = options->name;
    STEWART_CUEING_OPTION_TABLE(COPY_OPTION)
#undef COPY_OPTION
    c->message[0] = '\0';
    c->design = stewart::cueing::classical_design(*options, g, model->frames.z_down);
    c->limits = limits;
    c->legs = nullptr;
    c->limiter.limits = limits;
    c->limiter.frames = &model->frames;
    const double home[6] = {0, 0, model->params.home_height, 0, 0, 0};
    std::memcpy(c->limiter.home, home, sizeof home);
    c->limiter.rate = options->limiter_rate;
    c->limiter.accel = options->limiter_accel;
    c->limiter.lookahead = options->limiter_lookahead;
    rest(c->state);
    if (!make_leg_solver(*c, msg, size) || !home_within(*c, msg, size)) {
        stewart_cueing_free(c);
        return nullptr;
    }
    clear_message(msg, size);
    return c;
}

void stewart_cueing_free(stewart_cueing *c) {
    if (!c) return;
    stewart_limits_free(c->limits);
    stewart_inverse_free(c->legs);
    delete c;
}

void stewart_cueing_reset(stewart_cueing *c) {
    if (!c) return;
    rest(c->state);
    c->message[0] = '\0';
}

stewart_status stewart_cueing_copy(stewart_cueing *dst, const stewart_cueing *src) {
    if (!dst || !src) return STEWART_ERR_ARGUMENT;
    if (dst->model != src->model || std::memcmp(&dst->options, &src->options, sizeof dst->options))
        return set_message(dst->message, sizeof dst->message, STEWART_ERR_ARGUMENT,
                           "copy from a cueing object of another model or other options");
    dst->state = src->state;
    return clear_message(dst->message, sizeof dst->message);
}

size_t stewart_cueing_state_size(const stewart_cueing *) { return sizeof(SavedState); }

stewart_status stewart_cueing_save(const stewart_cueing *c, void *buffer, size_t size) {
    if (!c) return STEWART_ERR_ARGUMENT;
    if (!buffer || size < sizeof(SavedState))
        return set_message(c->message, sizeof c->message, STEWART_ERR_ARGUMENT,
                           "the buffer needs %zu bytes", sizeof(SavedState));
    SavedState saved;
    std::memset(&saved, 0, sizeof saved);
    saved.tag = kStateTag;
    saved.options = c->options;
    saved.state = c->state;
    std::memcpy(buffer, &saved, sizeof saved);
    return clear_message(c->message, sizeof c->message);
}

stewart_status stewart_cueing_load(stewart_cueing *c, const void *buffer, size_t size) {
    if (!c) return STEWART_ERR_ARGUMENT;
    if (!buffer || size != sizeof(SavedState))
        return set_message(c->message, sizeof c->message, STEWART_ERR_ARGUMENT,
                           "a cueing state is %zu bytes, not %zu", sizeof(SavedState), size);
    SavedState saved;
    std::memcpy(&saved, buffer, sizeof saved);
    if (saved.tag != kStateTag || std::memcmp(&saved.options, &c->options, sizeof c->options) ||
        !finite_state(saved.state))
        return set_message(c->message, sizeof c->message, STEWART_ERR_ARGUMENT,
                           "the bytes are not a state of a cueing object with these options");
    c->state = saved.state;
    return clear_message(c->message, sizeof c->message);
}

const char *stewart_cueing_message(const stewart_cueing *c) {
    return c ? c->message : "cueing is NULL";
}

stewart_status stewart_cueing_step(stewart_cueing *c, const stewart_cueing_input *in,
                                   stewart_cueing_output *out) {
    if (!c) return STEWART_ERR_ARGUMENT;
    const stewart_status status = check_input(c, in, out);
    if (status != STEWART_OK) return status;
    CueingState next = c->state;
    stewart::cueing::Excursion e;
    stewart::cueing::classical_step(c->design, c->steps, next.classical, *in, e);
    const stewart::cueing::Scale s =
        stewart::cueing::limited_scale(c->limiter, e, c->state.scale, c->state.scale_rate, in->dt);
    next.scale = s.value;
    next.scale_rate = s.rate;
    // The pose home + s e: rate s e' + s' e, acceleration s e'' + 2 s' e' + s'' e.
    stewart_pose scaled;
    for (int i = 0; i < 6; ++i) {
        scaled.q[i] = c->limiter.home[i] + s.value * e.q[i];
        scaled.q_dot[i] = s.value * e.q_dot[i] + s.rate * e.q[i];
        scaled.q_ddot[i] = s.value * e.q_ddot[i] + 2.0 * s.rate * e.q_dot[i] + s.accel * e.q[i];
    }
    stewart_pose platform;
    const bool legs_limited =
        stewart::cueing::leg_limited_step(c->leg_limiter, scaled, in->dt, next.output, platform);
    stewart_cueing_output o;
    if (!stewart::cueing::caller_pose(c->limiter, platform, 2, o.pose))
        return set_message(c->message, sizeof c->message, STEWART_ERR_ARGUMENT,
                           "the tool's pitch reaches 90 deg, where its rates are not defined: "
                           "reduce the cue's angles (roll_scale, pitch_scale, tilt_max)");
    for (int i = 0; i < 6; ++i)
        if (!std::isfinite(o.pose.q[i]) || !std::isfinite(o.pose.q_dot[i]) ||
            !std::isfinite(o.pose.q_ddot[i]))
            return set_message(c->message, sizeof c->message, STEWART_ERR_ARGUMENT,
                               "the input overflows the cue: reduce it or the scales");
    o.scale = next.scale;
    o.limited = next.scale < 1.0 || legs_limited;
    o.cut = s.cut;
    o.tilt_limited = e.tilt_limited;
    o.leg_limits = broken_leg_limits(*c, o.pose);
    c->state = next;
    *out = o;
    return STEWART_OK;
}

}  // extern "C"
