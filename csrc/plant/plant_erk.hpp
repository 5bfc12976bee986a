// ARKODE's explicit Runge-Kutta step (ERKStep: its fixed-step mode, and its adaptive mode with the
// default PI controller) written out for the plant's 13 states, one communication step [0, h]
// with the stop time at h: the same stages, error estimate, step-size control, stop-time
// clipping, end-of-step evaluation and output, in the same arithmetic and order, so the same
// bits, without ARKODE's restart and per-step bookkeeping (about 20 k instructions per 1 ms
// step). What it does not reproduce (a failed right-hand side, a root of the pitch function,
// the step or error-test limits) it hands back: the caller then runs the step with ARKODE.
#pragma once

namespace stewart {
namespace plant {

constexpr int kStates = 13;  // the platform: position, quaternion, velocity, angular velocity
// and, with the windings' currents as states (voltage input, an inductance), six more
constexpr int kMaxStates = kStates + 6;
constexpr int kMaxErkStages = 5;

// An explicit Butcher table with an embedding, of at most kMaxErkStages stages, whose last stage
// is not at the step's end (so ARKODE evaluates the right-hand side again there): ERK 4(3).
struct ErkTable {
    int stages = 0, embedding_order = 0;
    double A[kMaxErkStages][kMaxErkStages] = {};
    double b[kMaxErkStages] = {}, d[kMaxErkStages] = {}, c[kMaxErkStages] = {};
};

// ARKODE's table `table_number` (an ARKODE_ERKTableID) copied; false if it does not fit ErkTable.
bool load_erk_table(int table_number, ErkTable &table);

// A change of the state in place (the quaternion's normalisation).
using ErkProject = void (*)(double *y);

// How a communication step is divided, as the ERKStep options the plant sets.
struct ErkControl {
    int fixed_steps = 0;    // N equal steps (ERKStepSetFixedStep(h / N)); 0: adaptive
    double first_step = 0;  // adaptive: ERKStepSetInitStep, > 0
    double relative_tolerance = 0, absolute_tolerance = 0;  // ERKStepSStolerances
    long max_steps = 0;                                     // ERKStepSetMaxNumSteps
    // Not ARKODE's (both off in its copy): the work's F[0] already holds the right-hand side at
    // (0, y0) (the last step's end evaluation, carried; rhs_evaluations counts it all the same,
    // as ARKODE would); and the state that reaches the stop time projected before its end
    // evaluation, which then is at the state returned (y_out).
    bool start_rate_known = false;
    ErkProject project_end = nullptr;
};

// The right-hand side dy/dt at (t, y): 0 on success, else the caller's flag.
using ErkRhs = int (*)(double t, const double *y, double *y_dot, void *user);
// The pitch root function g at y (ARKODE's root function on raw arrays).
using ErkRoot = double (*)(const double *y, void *user);

// The vectors of one communication step, made once (a step allocates nothing).
struct ErkWork {
    double F[kMaxErkStages][kMaxStates];        // stage derivatives; F[0] at the step's start
    double yn[kMaxStates], ycur[kMaxStates];    // the step's start, the stage or new state
    double yold[kMaxStates], fold[kMaxStates];  // the last step's start and its derivative
    double weight[kMaxStates], error[kMaxStates];
};

// What one communication step did (ARKODE's counters of the same run).
struct ErkResult {
    bool done = false;  // false: hand the step to ARKODE (nothing of the caller's changed)
    long steps = 0, rhs_evaluations = 0, error_test_failures = 0;
    double last_step = 0;  // ERKStepGetLastStep
    double next_step = 0;  // ERKStepGetCurrentStep after the step (the next first step)
    // project_end was applied: work.yn, y_out and the end evaluation's state are the same bits,
    // and work.F[0] is the right-hand side there at the stop time
    bool end_projected = false;
};

// Integrates y0 over [0, h_comm] as ERKStepEvolve(h_comm) after ERKStepReInit with the stop
// time h_comm and `control`, into y_out; g_start is the root function at y0. The right-hand
// side's last evaluation is at (h_comm, the new state before y_out's interpolation); with
// control.project_end, at (h_comm, y_out) (end_projected).
// states: kStates or kMaxStates, the length of y0, y_out and the right-hand side's vectors.
ErkResult erk_advance(const ErkTable &table, const ErkControl &control, ErkWork &work,
                      double h_comm, const double *y0, double g_start, ErkRhs rhs, ErkRoot root,
                      void *user, double *y_out, int states = kStates);

}  // namespace plant
}  // namespace stewart
