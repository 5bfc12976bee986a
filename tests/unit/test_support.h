/* Shared helpers of the Unity tests: models, poses, and trajectories with exact derivatives. */
#ifndef STEWART_TEST_SUPPORT_H
#define STEWART_TEST_SUPPORT_H

#include <stdint.h>

#include "stewart/stewart.h"
#include "stewart/stewart_forward.h"
#include "stewart/stewart_plant.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Fails the current test (with the library's message) if the model cannot be built. */
stewart_model *test_model(const stewart_params *params);
stewart_inverse_options test_options(stewart_fidelity fidelity);

/* A smooth combined manoeuvre: every pose component a sinusoid (amplitudes within the thesis
 * platform's workspace), with exact first and second derivatives. */
stewart_pose combined_pose(double t);
/* One thesis manoeuvre at 5 rad/s: component 2 (z) heave of 0.04 m about 0.5 m, or component
 * 3/4/5 (roll/pitch/yaw) of amplitude pi/18 with z held at 0.5 m. */
stewart_pose thesis_pose(int component, double t);

/* R = Rz(yaw) Ry(pitch) Rx(roll) of the pose, written out (docs/model.md). */
void pose_rotation(const stewart_pose *pose, double R[3][3]);
/* Leg k's length |p + R b_k - a_k| from the pose and the attachment points of params (the circles,
 * or the joints when geometry is 1), written out here: the reference the library's lengths are
 * checked against. */
double closed_form_length(const stewart_params *params, const stewart_pose *pose, int k);

/* An inverse solver for m with the default options; fails the test if it cannot be made. */
stewart_inverse *test_inverse(const stewart_model *m);
/* An inverse solver for m with the options o; fails the test if it cannot be made. */
stewart_inverse *test_inverse_with(const stewart_model *m, const stewart_inverse_options *o);
/* A forward solver for m with the default options; fails the test if it cannot be made. */
stewart_forward *test_forward(const stewart_model *m);
/* The plant's default options at fidelity, and a plant for m with options o (fails the test
 * with the library's message if it cannot be made). */
stewart_plant_options test_plant_options(int fidelity);
stewart_plant *test_plant_with(const stewart_model *m, const stewart_plant_options *o);
/* stewart_inverse_solve as with options o from d's state: a solver made with o takes d's state
 * (stewart_inverse_copy), solves, and gives its state and message back to d. The tests' way to
 * vary the options along one history. */
stewart_status solve_as(stewart_inverse *d, const stewart_inverse_options *o,
                        const stewart_pose *pose, stewart_inverse_output *out);
/* Solves and fails the test with the library's message unless the status is STEWART_OK. */
stewart_inverse_output solve_ok(stewart_inverse *d, stewart_fidelity f, const stewart_pose *pose);

/* xorshift64*: the next number of a fixed-seed random sequence (the same run every time). */
uint64_t test_random(uint64_t *state);
/* A value a corrupted file or a careless caller might hold instead of v: one bit flipped, a
 * special value (0, 1e15, DBL_MAX, subnormal, NaN, inf, ...), a small relative change, 2 pi added,
 * the sign changed, or a random magnitude. */
double corrupted_value(uint64_t *rng, double v);

#ifdef __cplusplus
}
#endif

#endif
