/*
 * A general multibody kinematics and inverse-dynamics core: the C API. It stands alone (library
 * mbs, no header of the Stewart platform); the platform library and the slider-crank example
 * (examples/slider_crank) are built on it.
 *
 * A mechanism is data: add bodies and joints to an mbs_model, finalise it, then make one mbs_data
 * per independent run and step it. Bodies have reference-point coordinates q = (r, p): the
 * position of the centre of mass and the Euler parameters of the principal axes
 * (MBS_BODY_COORDINATES = 7 per body, MBS_BODY_R and MBS_BODY_P locate them). All vectors given
 * to a joint are in the frames of its bodies. Any consistent units (SI in the examples; the
 * Stewart platform measures lengths in a power-of-two unit near its size). No global state.
 *
 * Drivers prescribe a function of time; the caller gives its value, first and second time
 * derivative before each step (mbs_set_driver). A driver's multiplier is the generalised force
 * it applies (see each driver).
 */
#ifndef MBS_MBS_H
#define MBS_MBS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Room for any message of the core (mbs_model_message, mbs_data_message). */
#define MBS_MESSAGE_SIZE 256

/* Negative values are errors; mbs_model_message or mbs_data_message says which value and why.
 * The values are those of the Stewart library's statuses of the same meaning. */
typedef enum mbs_status {
    MBS_OK = 0,
    MBS_ERR_ARGUMENT = -1,      /* null pointer, index out of range, non-finite or corrupt input */
    MBS_ERR_PARAMETER = -2,     /* a body or joint property out of range, or a bad mechanism */
    MBS_ERR_SINGULAR = -3,      /* the constraint Jacobian is singular */
    MBS_ERR_NOT_CONVERGED = -5, /* the position Newton problem did not converge */
    MBS_ERR_MEMORY = -7
} mbs_status;

/* Defaults of mbs_options (and of the Stewart library's options of the same name). */
#define MBS_DEFAULT_TOLERANCE 1e-12
#define MBS_DEFAULT_MAX_ITERATIONS 20

/* Each body has MBS_BODY_COORDINATES coordinates in q (and in q_dot, q_ddot), body after body:
 * its position r (3), then its Euler parameters p (4). */
#define MBS_BODY_COORDINATES 7
#define MBS_BODY_R(body) (MBS_BODY_COORDINATES * (body))     /* index of body's r in q */
#define MBS_BODY_P(body) (MBS_BODY_COORDINATES * (body) + 3) /* index of body's p in q */

typedef struct mbs_model mbs_model;
typedef struct mbs_data mbs_data;

typedef enum mbs_linear_solver {
    MBS_LINEAR_AUTOMATIC = 0, /* bordered-block LU if the structure is there, else dense LU */
    MBS_LINEAR_DENSE = 1,     /* our dense LU behind KINSOL */
    MBS_LINEAR_BLOCK = 2,     /* bordered-block LU, or mbs_data_create fails */
    MBS_LINEAR_KINSOL_DENSE =
        3 /* KINSOL's SUNDenseMatrix + SUNLinSol_Dense for Newton (baseline) */
} mbs_linear_solver;

typedef struct mbs_options {
    double tolerance;    /* max-norm of the position residual; MBS_DEFAULT_TOLERANCE */
    int max_iterations;  /* MBS_DEFAULT_MAX_ITERATIONS */
    int modified_newton; /* 0 exact Newton, 1 Jacobian kept across iterations; 0 */
    int use_predictor;   /* 1: start Newton from q + h q_dot + h^2/2 q_ddot; 1 */
} mbs_options;

void mbs_options_default(mbs_options *options);

mbs_model *mbs_model_create(void);
void mbs_model_free(mbs_model *model);
/* The message of the last call on this model that failed, else "". */
const char *mbs_model_message(const mbs_model *model);
/* Gravity, world frame [m/s^2]; default zero. */
mbs_status mbs_set_gravity(mbs_model *model, const double gravity[3]);

/* Returns the body index (>= 0) or a negative mbs_status. inertia: principal moments about
 * the centre of mass; q_reference: the assembly configuration (r, p), also the first guess. */
int mbs_add_body(mbs_model *model, const char *name, double mass, const double inertia[3],
                 const double q_reference[7]);
/* The body's coordinates stay at its reference configuration (7 equations). */
mbs_status mbs_fix_body(mbs_model *model, int body);

/* Joints return the joint index (>= 0) or a negative mbs_status. u_*: attachment point in
 * the body frame; s_*, v_*: directions in the body frame (need not be unit). */
int mbs_add_spherical(mbs_model *m, int body_i, const double u_i[3], int body_j,
                      const double u_j[3]);
/* Cross arms s_i (on body i) and s_j (on body j) stay perpendicular. */
int mbs_add_cardan(mbs_model *m, int body_i, const double u_i[3], const double s_i[3], int body_j,
                   const double u_j[3], const double s_j[3]);
/* Axes v_i and v_j stay collinear through the points; the distance along it is free. */
int mbs_add_cylindrical(mbs_model *m, int body_i, const double u_i[3], const double v_i[3],
                        int body_j, const double u_j[3], const double v_j[3]);
int mbs_add_revolute(mbs_model *m, int body_i, const double u_i[3], const double v_i[3], int body_j,
                     const double u_j[3], const double v_j[3]);
/* As cylindrical, and the relative rotation about the axis stays as in the reference. */
int mbs_add_prismatic(mbs_model *m, int body_i, const double u_i[3], const double v_i[3],
                      int body_j, const double u_j[3], const double v_j[3]);
/* Points coincide, relative orientation stays as in the reference configuration. */
int mbs_add_weld(mbs_model *m, int body_i, const double u_i[3], int body_j, const double u_j[3]);

/* Drivers return the joint index; *driver (if not NULL) receives the driver slot. */
/* q_body[coordinate] = f(t), coordinate 0..6. Multiplier: minus the generalised force. */
int mbs_add_coordinate_driver(mbs_model *m, int body, int coordinate, int *driver);
/* The body's 7 coordinates = f(t) (7 slots, r then p); replaces its normalisation. */
int mbs_add_pose_driver(mbs_model *m, int body, int *driver);
/* Distance along a cylindrical or prismatic joint's axis between its points = f(t): an actuator.
 * Multiplier: minus the force pushing body j away from body i along the axis. */
int mbs_add_distance_driver(mbs_model *m, int joint, int *driver);
/* Rotation of body j relative to body i about a revolute joint's axis = f(t), measured from the
 * reference configuration, positive about v_i. Multiplier: the torque driving body j. */
int mbs_add_angle_driver(mbs_model *m, int joint, int *driver);

/* Adds the normalisations and plans the solver; the model is immutable afterwards. */
mbs_status mbs_model_finalize(mbs_model *m, char *message, size_t size);
int mbs_coordinate_count(const mbs_model *m);
int mbs_equation_count(const mbs_model *m);
/* First equation row of a joint (its multipliers start there in mbs_lambda). */
int mbs_joint_first_row(const mbs_model *m, int joint);

/* NULL if the model is not finalised or memory is short. */
mbs_data *mbs_data_create(const mbs_model *m, mbs_linear_solver solver);
void mbs_data_free(mbs_data *d);
/* Copies the state of src into dst (both of the same model, else MBS_ERR_ARGUMENT). */
mbs_status mbs_data_copy(mbs_data *dst, const mbs_data *src);
const char *mbs_data_message(const mbs_data *d);

mbs_status mbs_set_driver(mbs_data *d, int driver, double value, double rate, double accel);
/* Position, velocity, acceleration and multipliers at time t. */
mbs_status mbs_step(mbs_data *d, double t, const mbs_options *options);

const double *mbs_q(const mbs_data *d);
const double *mbs_q_dot(const mbs_data *d);
const double *mbs_q_ddot(const mbs_data *d);
const double *mbs_lambda(const mbs_data *d);
int mbs_iterations(const mbs_data *d);
double mbs_residual(const mbs_data *d);
/* How many times the block solver's factorisation of a group left its planned pivot order for
 * partial pivoting since d was made (0 for the dense solver). The results stay right either way;
 * a normal path should take no fallback, so this is what shows one. */
long mbs_linear_fallbacks(const mbs_data *d);
/* Force and torque (world frame; torque about the body's centre of mass) that a joint puts on
 * its body i (side 0) or body j (side 1). */
mbs_status mbs_joint_reaction(const mbs_data *d, int joint, int side, double force[3],
                              double torque[3]);

/* Diagnostics: Phi, Phi_q (dense, row-major equations x coordinates), Phi_t and gamma at any q
 * and q_dot with the current driver values. Any output may be NULL; q_dot only for gamma. */
mbs_status mbs_evaluate(const mbs_data *d, const double *q, const double *q_dot, double *phi,
                        double *jacobian, double *phi_t, double *gamma);
/* Kinetic plus potential energy of all bodies at q, q_dot. */
double mbs_energy(const mbs_data *d, const double *q, const double *q_dot);

#ifdef __cplusplus
}
#endif

#endif /* MBS_MBS_H */
