/*
 * The controller's current-output mode (output = 1): per leg a cascade as a servo drive runs it,
 * on the motor's side of the leg's drive (docs/drives.md, "Closing the loop on currents"):
 *
 *   theta_err = c (L_ref - L)                                 position error at the motor [rad]
 *   omega_cmd = c L_dot_ref + position_gain theta_err        limited to +-motor_speed_max
 *   e         = omega_cmd - c L_dot                           speed error [rad/s]
 *   tau       = speed_gain (e + z / speed_integral_time)      z = integral of e [rad]
 *   i         = i_ff + tau / torque_constant                  limited to +-current_max
 *
 * with c = 2 pi gear_ratio / screw_lead the motor angle per leg length, as the drive law
 * (csrc/drives/leg_drive.hpp, motor_per_leg) defines it, and i_ff the inverse unit's current.
 */
#ifndef STEWART_CONTROLLER_CASCADE_H
#define STEWART_CONTROLLER_CASCADE_H

/* One leg's drive as the cascade sees it. */
typedef struct cascade_drive {
    double motor_per_leg;   /* c [rad/m] */
    double torque_constant; /* [N m/A] */
    double current_max;     /* [A], 0: no limit */
    double motor_speed_max; /* [rad/s], 0: no limit */
} cascade_drive;

/* The gains, common to the legs. */
typedef struct cascade_gains {
    double position;      /* [1/s] */
    double speed;         /* [N m s/rad] */
    double integral_time; /* [s], 0: no integral */
} cascade_gains;

/* The leg's five inputs, in the controller's input order. */
enum {
    CASCADE_L_REF,
    CASCADE_L_DOT_REF,
    CASCADE_FEED_FORWARD,
    CASCADE_L,
    CASCADE_L_DOT,
    CASCADE_INPUTS
};

/* One evaluation: the current command, the speed error the integral takes, which limit holds,
 * and d current / d input (0 for the inputs a limit cuts off). */
typedef struct cascade_result {
    double current, speed_error;
    int speed_limited, current_limited;
    double slope[CASCADE_INPUTS];
} cascade_result;

/* c = 2 pi N / lead: the drive law's motor angle per leg length (0 for no screw). */
double cascade_motor_per_leg(double screw_lead, double gear_ratio);

/* The cascade for one leg at inputs in[CASCADE_INPUTS] and speed-error integral z [rad]. */
cascade_result cascade_leg(const cascade_drive *d, const cascade_gains *g,
                           const double in[CASCADE_INPUTS], double z);

/* The integral after a step of h with the inputs held: z + h e, or z where the current is at its
 * limit and e pushes further into it (conditional integration: no wind-up). */
double cascade_integrate(const cascade_result *r, const cascade_gains *g, double z, double h);

#endif
