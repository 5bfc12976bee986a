// Forward dynamics, time integration: CVODE or ARKODE on the 13 states (platform origin, unit
// quaternion, velocity, angular velocity, world frame), restarted at every communication step
// because the inputs change there; ERK 4(3) by its written-out copy (plant_erk.hpp, the same
// bits), ARKODE where the copy hands a step back.
#pragma once

#include "plant/plant_equations.hpp"
#include "plant/plant_erk.hpp"
#include "stewart/stewart_plant.h"

namespace stewart {
namespace plant {

// The six forces over one communication step [0, h]: linear between the end values, or cubic
// Hermite when the end rates are known.
struct ForceProfile {
    double h = 1;
    double start[STEWART_LEGS] = {0}, end[STEWART_LEGS] = {0};
    double start_rate[STEWART_LEGS] = {0}, end_rate[STEWART_LEGS] = {0};
    bool hermite = false;
    // The forces at tau in [0, h].
    void at(double tau, double force[STEWART_LEGS]) const;
};

// The platform motion (pose and twist; zero accelerations) of a state vector; the quaternion is
// normalised on the way.
Motion motion_of_state(const double y[kStates]);

// Roll, pitch, yaw of a state's rotation on the principal branch (pitch in [-pi/2, pi/2]).
void principal_angles(const double y[kStates], double a[3]);
// Whether the motion from principal angles `before` to `after` took pitch through +-90 degrees.
bool crosses_pitch_limit(const double before[3], const double after[3]);
// True if y's rotation is so near start's (whose principal pitch is start_pitch, near level)
// that crosses_pitch_limit is false for their angles: the pitch root's cheap pre-test.
bool near_level_turn(const double start[kStates], double start_pitch, const double y[kStates]);

// The integrator's states for this model: kStates (the platform), or kMaxStates with the
// windings' currents after them (voltage input and an inductance).
inline int state_count(const DynamicsModel &d) { return d.drives.inductive ? kMaxStates : kStates; }

struct IntegratorImpl;

// One CVODE or ARKODE instance and its workspaces, made once; advance() allocates nothing.
class Integrator {
public:
    Integrator() = default;
    Integrator(const Integrator &) = delete;
    Integrator &operator=(const Integrator &) = delete;
    ~Integrator();
    // False (message says why) if SUNDIALS cannot be set up. written_out: ERK 4(3) steps by
    // plant_erk.hpp's copy of ARKODE's (the same bits), ARKODE only where it hands a step back;
    // false: ARKODE alone (the reference of tests/unit/test_plant_erk.cpp). carry_end (written
    // out only): the step's last internal step normalises the quaternion before its end
    // evaluation (the state returned is the same bits: advance() normalises it with the same
    // arithmetic otherwise), so that evaluation is the next step's start derivative when it
    // starts there under the same forces: one right-hand side fewer per step (rhs_evaluations
    // still counts it, as ARKODE's count: the statistics do not depend on what was carried, so
    // a rollback repeats them); the end evaluation is at the state returned. false: ARKODE's.
    bool init(const DynamicsModel *model, const stewart_plant_options &options, char *msg,
              size_t size, bool written_out = true, bool carry_end = true);
    // Integrates y (state_count(*model) values) over [0, h]. On failure y is unchanged and the message names the cause
    // (the leg, or the integrator's flag and text). Normalises the quaternion of the result.
    // step_hint: the first internal step to try (0: the integrator estimates it); on success,
    // the step the integrator would take next (explicit Runge-Kutta only; CVODE ignores it).
    // start_angles: principal_angles(y) if the caller has them (or nullptr).
    stewart_status advance(double *y, const ForceProfile &forces, double &step_hint, char *msg,
                           size_t size, const double *start_angles = nullptr);
    // The right-hand side's last evaluation if it was at the end of the last successful
    // advance() (tau = h, the end forces, the state the integrator returned: before the
    // quaternion's normalisation, or after it with carry_end), else nullptr: the step's outputs reuse it instead of
    // evaluating the same equations again (ERK's end-of-step evaluation is exactly that one).
    // For the massless model its legs[] are not filled (Evaluation::fill_legs).
    const Evaluation *end_evaluation() const;
    // Whether the last advance took its start's right-hand side from the step before (carry_end).
    bool start_carried() const;
    // Counters of the last advance (the totals are the caller's).
    const stewart_plant_statistics &statistics() const { return stats_; }

private:
    // The end of a successful advance: whether the last evaluation is the step's end, the
    // quaternion normalised (unless it is already), the state checked and copied to y.
    stewart_status finish_step(double *y, double h, char *msg, size_t size,
                               bool normalized = false);
    IntegratorImpl *impl_ = nullptr;
    stewart_plant_statistics stats_{};
};

}  // namespace plant
}  // namespace stewart
