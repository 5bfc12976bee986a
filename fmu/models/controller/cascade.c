/* The current-output cascade of one leg (cascade.h). */
#include "cascade.h"

#include <math.h>

static const double kPi = 3.14159265358979323846;

double cascade_motor_per_leg(double screw_lead, double gear_ratio) {
    return screw_lead > 0 ? 2.0 * kPi * gear_ratio / screw_lead : 0.0;
}

/* x within +-limit (limit 0: no limit); *limited set when it was cut. */
static double within(double x, double limit, int *limited) {
    *limited = limit > 0 && fabs(x) > limit;
    return *limited ? copysign(limit, x) : x;
}

cascade_result cascade_leg(const cascade_drive *d, const cascade_gains *g,
                           const double in[CASCADE_INPUTS], double z) {
    cascade_result r = {0};
    const double c = d->motor_per_leg, kt = d->torque_constant;
    const double command =
        c * in[CASCADE_L_DOT_REF] + g->position * c * (in[CASCADE_L_REF] - in[CASCADE_L]);
    const double omega_cmd = within(command, d->motor_speed_max, &r.speed_limited);
    r.speed_error = omega_cmd - c * in[CASCADE_L_DOT];
    const double integral = g->integral_time > 0 ? z / g->integral_time : 0.0;
    const double torque = g->speed * (r.speed_error + integral);
    r.current = within(in[CASCADE_FEED_FORWARD] + torque / kt, d->current_max, &r.current_limited);
    if (r.current_limited) return r;        /* the slopes stay 0 */
    const double per_speed = g->speed / kt; /* d current / d omega_cmd */
    r.slope[CASCADE_FEED_FORWARD] = 1.0;
    r.slope[CASCADE_L_DOT] = -per_speed * c;
    if (!r.speed_limited) {
        r.slope[CASCADE_L_DOT_REF] = per_speed * c;
        r.slope[CASCADE_L_REF] = per_speed * g->position * c;
        r.slope[CASCADE_L] = -r.slope[CASCADE_L_REF];
    }
    return r;
}

double cascade_integrate(const cascade_result *r, const cascade_gains *g, double z, double h) {
    if (!(g->integral_time > 0)) return z;
    if (r->current_limited && r->speed_error * r->current > 0) return z;
    return z + h * r->speed_error;
}
