/*
 * Motion cueing (docs/cueing.md): a vehicle's specific force and angular velocity in, the
 * platform's pose with its rates and accelerations out, within every limit of the machine.
 *
 * A cueing object is made from a model and its options like the other directions' objects
 * (stewart_cueing_create, _free, _reset, _copy, _state_size, _save, _load, _message) and takes
 * one sample per call:
 *   stewart_cueing_step(cueing, &input, &output)
 *
 * Vehicle input: specific force f [m/s2] and angular velocity w [rad/s] in the vehicle frame at
 * the pilot's head, x forward, y left, z up: a vehicle at rest reads f = (0, 0, +g) with g the
 * magnitude of the model's gravity.
 *
 * Algorithm STEWART_CUEING_CLASSICAL, the classical washout (Reid & Nahon 1985), per axis and
 * each filter linear and discretised exactly (zero-order hold, the matrix exponential):
 *   translation  x_i = k_i H_t(s) / s^2 (f_i - f_rest,i), H_t = s^2 / (s^2 + 2 zeta w s + w^2)
 *                (translation_order 2) or that times s / (s + w_b) (order 3)
 *   tilt         f_lp,i = k_i w_l^2 / (s^2 + 2 zeta_l w_l s + w_l^2) f_i (i = x, y);
 *                pitch_tilt = -asin(f_lp,x / g), roll_tilt = asin(f_lp,y / (g cos pitch_tilt)),
 *                each at most tilt_max and moving at most tilt_rate_max
 *   rotation     angle_i = k_i H_r(s) / s w_i, H_r = s^2 / (s^2 + 2 zeta_r w_r s + w_r^2)
 *                (rotation_filter_order 2) or s / (s + w_r) (order 1)
 * The platform turns about the head (head_x, head_y, head_z in the machine's platform frame, z
 * down with frame_convention 1): its origin moves by (I - R) head besides the translation. The
 * excursion is added to the home pose.
 *
 * The limiter then enforces the machine's limits (stewart_limits_check: strokes, joint angles,
 * interference, condition, axis ranges) on every output pose: the excursion from home is scaled
 * by s in [0, 1], s moving toward the largest scale within the limits now and at the excursion
 * extrapolated lookahead / 2 and lookahead seconds ahead, its rate at most limiter_rate and its
 * acceleration at most limiter_accel, and cut at once to a scale within the limits (bisection
 * along the excursion) when that is not enough. The output's rates and accelerations are those of
 * the scaled trajectory (s a cubic over each step, s' continuous but at a cut).
 *
 * When the platform gives leg_speed_max or leg_accel_max, a leg limiter then keeps every output
 * sample's leg rates and accelerations within them: the output follows the scaled pose exactly
 * while its legs, the step to it and the pose where it would stop (braking on half the
 * acceleration limit) pass, and otherwise moves at a constant pose acceleration over the step
 * (the cue's plus a critically damped pull toward it, scaled down to pass; else a brake; else a
 * hold at the last pose, the pose limits first). It reports, not enforces, leg_force_max
 * (leg_limits); it neither enforces nor reports leg_jerk_max; nor does it check the poses between
 * samples.
 *
 * Never allocates after _create, never writes NaN.
 */
#ifndef STEWART_STEWART_CUEING_H
#define STEWART_STEWART_CUEING_H

#include <stddef.h>

#include "stewart/stewart.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The algorithms (option algorithm). */
typedef enum stewart_cueing_algorithm {
    STEWART_CUEING_CLASSICAL = 0 /* classical washout with tilt coordination (Reid & Nahon) */
} stewart_cueing_algorithm;
#define STEWART_CUEING_ALGORITHMS 1

/* Bits of stewart_cueing_output.leg_limits. */
#define STEWART_CUEING_LEG_SPEED 1
#define STEWART_CUEING_LEG_ACCEL 2
#define STEWART_CUEING_LEG_FORCE 4

/* Settings of a cueing object, in the order of STEWART_CUEING_OPTION_TABLE (stewart_table.h,
 * where each one's range and default are); stewart_cueing_options_default gives the defaults. */
typedef struct stewart_cueing_options {
    int algorithm;                               /* stewart_cueing_algorithm */
    double surge_scale, sway_scale, heave_scale; /* k_x, k_y, k_z of the specific force [1] */
    double roll_scale, pitch_scale, yaw_scale;   /* k of the angular velocity [1] */
    int translation_order;                /* 2 or 3: the high-pass order of the translation */
    double translation_frequency;         /* w [rad/s] */
    double translation_damping;           /* zeta [1] */
    double translation_washout_frequency; /* w_b [rad/s] of order 3 */
    double tilt_frequency;                /* w_l [rad/s] of the tilt low-pass */
    double tilt_damping;                  /* zeta_l [1] */
    double tilt_max;                      /* largest tilt angle [rad] */
    double tilt_rate_max;                 /* largest tilt rate [rad/s] */
    int rotation_filter_order;            /* 1 or 2: the high-pass order of the rotation */
    double rotation_frequency;            /* w_r [rad/s] */
    double rotation_damping;              /* zeta_r [1] (order 2) */
    double head_x, head_y, head_z;        /* the head in the machine's platform frame [m] */
    double limiter_rate;                  /* largest rate of the limiter's scale [1/s] */
    double limiter_lookahead;             /* how far ahead the limiter looks [s] */
    double limiter_accel;                 /* largest acceleration of the limiter's scale [1/s2] */
    double warn_condition;                /* the condition limit, as the limits' option [1] */
} stewart_cueing_options;

/* One sample: the vehicle's specific force and angular velocity, held over the dt seconds that
 * end at this sample (dt = 0: no time passes, e.g. the first sample of a run). */
typedef struct stewart_cueing_input {
    double dt;                  /* [s], >= 0 */
    double specific_force[3];   /* [m/s2], vehicle frame at the head, z up */
    double angular_velocity[3]; /* [rad/s], vehicle frame */
} stewart_cueing_input;

/* What a step gives: the pose as the inverse solver takes it (the tool in the user frame) at the
 * end of the step, with its exact rates and accelerations (accelerations with the input held). */
typedef struct stewart_cueing_output {
    stewart_pose pose;
    double scale;     /* the limiter's scale s of the excursion from home, in [0, 1] */
    int limited;      /* 1: the limiter scaled the cue down at this sample (s < 1), or the
                           output left the scaled cue for the legs' speed and acceleration limits */
    int cut;          /* 1: the smooth motion of s did not suffice and s was cut at once */
    int tilt_limited; /* 1: a tilt angle met tilt_max or tilt_rate_max at this sample */
    int leg_limits;   /* the legs' motion limits the pose breaks, checked when given: bit 1 a
                           leg's speed beyond leg_speed_max, 2 its acceleration beyond
                           leg_accel_max (both enforced: set only when the pose limits left no
                           motion within them), 4 its force (massless legs) beyond
                           leg_force_max (reported, not enforced) */
} stewart_cueing_output;

typedef struct stewart_cueing stewart_cueing;

/* The defaults of STEWART_CUEING_OPTION_TABLE. */
void stewart_cueing_options_default(stewart_cueing_options *options);
/* STEWART_OK, or STEWART_ERR_PARAMETER with a message naming the option and its value. */
stewart_status stewart_cueing_options_check(const stewart_cueing_options *options, char *message,
                                            size_t size);
/* A cueing object at rest at home for model (which must outlive it): NULL if an option is out of
 * range, the home pose is not within every limit, an argument is NULL or memory is short
 * (message says which). */
stewart_cueing *stewart_cueing_create(const stewart_model *model,
                                      const stewart_cueing_options *options, char *message,
                                      size_t size);
void stewart_cueing_free(stewart_cueing *cueing);
/* Back to rest at home, as if new. */
void stewart_cueing_reset(stewart_cueing *cueing);
/* Copies the state of src into dst (same model and options, else STEWART_ERR_ARGUMENT). */
stewart_status stewart_cueing_copy(stewart_cueing *dst, const stewart_cueing *src);
/* The state as bytes (rollback): its size, save, load (STEWART_ERR_ARGUMENT, state unchanged,
 * unless the bytes are a state of a cueing object of the same options). */
size_t stewart_cueing_state_size(const stewart_cueing *cueing);
stewart_status stewart_cueing_save(const stewart_cueing *cueing, void *buffer, size_t size);
stewart_status stewart_cueing_load(stewart_cueing *cueing, const void *buffer, size_t size);
/* The message of the last call that did not return STEWART_OK, else "". */
const char *stewart_cueing_message(const stewart_cueing *cueing);

/* One sample. STEWART_ERR_ARGUMENT (state and output untouched, message naming the value) for a
 * NULL argument, a non-finite input or dt < 0 or not finite. */
stewart_status stewart_cueing_step(stewart_cueing *cueing, const stewart_cueing_input *input,
                                   stewart_cueing_output *output);

#ifdef __cplusplus
}
#endif

#endif /* STEWART_STEWART_CUEING_H */
