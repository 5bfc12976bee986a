#include "plant/plant_integrator.hpp"

#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <type_traits>

#include "core/sundials_holder.hpp"
#include "plant/plant_erk.hpp"
#include "util/message.hpp"

namespace stewart {
namespace plant {

// The fixed-point solver's free function (the shared holder has none for nonlinear solvers).
struct NonlinearSolverFree {
    void operator()(SUNNonlinearSolver s) const { SUNNonlinSolFree(s); }
};

// The SUNDIALS objects are freed in reverse order of declaration: the integrators first, the
// context last.
struct IntegratorImpl {
    const DynamicsModel *model = nullptr;
    const ForceProfile *forces = nullptr;
    mbs::sundials::Context context;
    mbs::sundials::Vector y_holder;
    N_Vector y = nullptr;  // y_holder's vector
    mbs::sundials::Matrix matrix;
    mbs::sundials::LinearSolver linear;
    std::unique_ptr<std::remove_pointer_t<SUNNonlinearSolver>, NonlinearSolverFree> nonlinear;
    mbs::sundials::Memory<CVodeFree> cvode_holder;
    mbs::sundials::Memory<ERKStepFree> arkode_holder;
    void *cvode = nullptr;   // cvode_holder's memory
    void *arkode = nullptr;  // arkode_holder's: ERKStep, for STEWART_PLANT_ERK and _ERK5
    int erk_order = 0;
    int fixed_steps = 0;  // equal steps per communication step, or 0: adaptive
    long max_internal_steps = 0;
    // ERK 4(3) written out (plant_erk.hpp), ARKODE's when it hands a step back
    bool by_hand = false;
    ErkTable table;
    ErkWork work;
    double relative_tolerance = 0, absolute_tolerance = 0;
    double reference_angles[3] = {0, 0, 0};  // principal roll, pitch, yaw the pitch root follows
    int n = kStates;  // states: kStates, or kMaxStates with the windings' currents
    double start_state[kMaxStates] = {0};  // the communication step's start (pitch_sign's)
    Evaluation evaluation;
    LegFault fault = LegFault::None;  // the last right-hand side refused, and why
    int fault_leg = -1;
    bool non_finite = false;
    char cvode_message[160] = "";
    // the last successful right-hand side's arguments, and whether they were the step's end
    double last_tau = -1, last_y[kMaxStates] = {0}, last_force[STEWART_LEGS] = {0};
    bool end_valid = false;
    // whether state_rate copies its arguments (the written-out ERK knows its last ones itself)
    bool record_arguments = true;
    // The written-out ERK's last step ends with the quaternion normalised before its end
    // evaluation (carry_end), which the next step's start takes over when it starts from that
    // state (work.yn, bit for bit) under the same forces (carried_force): start_carried.
    bool carry_end = true;
    bool start_carried = false;
    double carried_force[STEWART_LEGS] = {0};
    bool last_start_carried = false;  // the last advance's start was carried
};

void ForceProfile::at(double tau, double force[STEWART_LEGS]) const {
    const double s = tau / h;
    if (s == 1) {  // the end values exactly (the step's outputs reuse this evaluation)
        for (int k = 0; k < STEWART_LEGS; ++k) force[k] = end[k];
        return;
    }
    if (!hermite) {
        for (int k = 0; k < STEWART_LEGS; ++k) force[k] = start[k] + s * (end[k] - start[k]);
        return;
    }
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2,
                 h11 = s3 - s2;
    for (int k = 0; k < STEWART_LEGS; ++k)
        force[k] = h00 * start[k] + h01 * end[k] + h * (h10 * start_rate[k] + h11 * end_rate[k]);
}

namespace {

// The state's quaternion scaled to unit norm (the step's end state, once).
void normalize_quaternion(double *y) {
    const double norm = std::sqrt(y[3] * y[3] + y[4] * y[4] + y[5] * y[5] + y[6] * y[6]);
    for (int i = 3; i < 7; ++i) y[i] /= norm;
}

// f(i) for each of the n states; the platform's 13 as a loop of known length (unrolled, as before
// the windings' currents could be states).
template <class F>
[[gnu::always_inline]] inline void each_state(int n, F f) {
    if (n == kStates)
        for (int i = 0; i < kStates; ++i) f(i);
    else
        for (int i = 0; i < n; ++i) f(i);
}

// Whether the right-hand side the last step carried (at work.yn and the end forces) is the one
// at the start of this step: the same state and forces at tau = 0, bit for bit.
bool start_rate_carried(const IntegratorImpl &im, const double *y, const ForceProfile &forces) {
    if (!im.start_carried) return false;
    double start_force[STEWART_LEGS];
    forces.at(0.0, start_force);
    return std::memcmp(y, im.work.yn, im.n * sizeof(double)) == 0 &&
           std::memcmp(start_force, im.carried_force, sizeof start_force) == 0;
}

// The state's quaternion (w, x, y, z) normalised as Eigen's Quaterniond normalize() (the squared
// norm summed as its two-wide packets, (x^2 + z^2) + (y^2 + w^2)), and the doubled components
// and products toRotationMatrix() forms from it: the same bits without its expression machinery
// (test_plant_rhs compares the rotation with Eigen's).
struct QuaternionProducts {
    double twx, twy, twz, txx, txy, txz, tyy, tyz, tzz;
};

QuaternionProducts quaternion_products(const double y[kStates]) {
    double w = y[3], x = y[4], yq = y[5], z = y[6];
    const double squared_norm = (x * x + z * z) + (yq * yq + w * w);
    if (squared_norm > 0) {
        const double norm = std::sqrt(squared_norm);
        w /= norm;
        x /= norm;
        yq /= norm;
        z /= norm;
    }
    const double tx = 2 * x, ty = 2 * yq, tz = 2 * z;
    return {tx * w, ty * w, tz * w, tx * x, ty * x, tz * x, ty * yq, tz * yq, tz * z};
}

}  // namespace

Motion motion_of_state(const double y[kStates]) {
    Motion m;
    m.position = Vec3(y[0], y[1], y[2]);
    // Eigen's normalize() and toRotationMatrix() written out in their order of operations.
    const QuaternionProducts t = quaternion_products(y);
    Mat3 &R = m.rotation;
    R(0, 0) = 1 - (t.tyy + t.tzz);
    R(0, 1) = t.txy - t.twz;
    R(0, 2) = t.txz + t.twy;
    R(1, 0) = t.txy + t.twz;
    R(1, 1) = 1 - (t.txx + t.tzz);
    R(1, 2) = t.tyz - t.twx;
    R(2, 0) = t.txz - t.twy;
    R(2, 1) = t.tyz + t.twx;
    R(2, 2) = 1 - (t.txx + t.tyy);
    m.velocity = Vec3(y[7], y[8], y[9]);
    m.omega = Vec3(y[10], y[11], y[12]);
    m.acceleration.setZero();
    m.alpha.setZero();
    return m;
}

// Roll, pitch, yaw of a state's rotation on the principal branch (pitch in [-pi/2, pi/2]), from
// the five entries of motion_of_state's rotation it reads (the same bits).
void principal_angles(const double y[kStates], double a[3]) {
    const QuaternionProducts t = quaternion_products(y);
    const double sp = -(t.txz - t.twy);
    a[1] = std::asin(sp > 1 ? 1 : sp < -1 ? -1 : sp);
    a[0] = std::atan2(t.tyz + t.twx, 1 - (t.txx + t.tyy));
    a[2] = std::atan2(t.txy + t.twz, 1 - (t.tyy + t.tzz));
}

// Whether the motion from angles `before` to `after` (both principal) took pitch through
// +-90 degrees: the other triple of the same rotation, (roll + pi, +-pi - pitch, yaw + pi), is
// nearer to `before` than `after` is, so angles kept continuous would have |pitch| > 90 degrees
// (roll and yaw jump by pi where pitch only touches 90 degrees on the principal branch).
bool crosses_pitch_limit(const double before[3], const double after[3]) {
    // |remainder(a, 2 pi)|; remainder is a itself where |a| <= fl(2 pi) / 2 (exactly)
    auto turn = [](double a) {
        return std::fabs(std::fabs(a) <= M_PI ? a : std::remainder(a, 2 * M_PI));
    };
    const double other_pitch = (after[1] >= 0 ? M_PI : -M_PI) - after[1];
    const double direct =
        turn(after[0] - before[0]) + std::fabs(after[1] - before[1]) + turn(after[2] - before[2]);
    const double other = turn(after[0] + M_PI - before[0]) + std::fabs(other_pitch - before[1]) +
                         turn(after[2] + M_PI - before[2]);
    return other < direct;
}

// pitch_sign's shortcut: a state whose rotation is within 0.1 rad of the start's (cos^2 of half
// the angle between the quaternions >= this), when the start's pitch is within kLevelPitch of
// level, crosses nothing. Along the shortest turn between them pitch stays within 1.3 rad of
// level (it moves no faster than the turn), so roll and yaw move by at most 0.1 / cos(1.3) =
// 0.37 rad each (|roll_dot|, |yaw_dot| <= |w| / cos(pitch)): crosses_pitch_limit's direct sum is
// at most 0.85 rad, the other triple's at least 2 (pi - 0.37) + (pi - 2.5) = 6.2 rad, far beyond
// the roundings of either. So the answer is the full test's, without its asin and atan2s.
constexpr double kNearTurnHalfCosSquared = 0.9976;  // > cos(0.05)^2 = 0.99750
constexpr double kLevelPitch = 1.2;

bool near_level_turn(const double start[kStates], double start_pitch, const double y[kStates]) {
    if (!(std::fabs(start_pitch) <= kLevelPitch)) return false;
    const double *q = y + 3, *q0 = start + 3;
    const double squared_norm = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    const double start_norm = q0[0] * q0[0] + q0[1] * q0[1] + q0[2] * q0[2] + q0[3] * q0[3];
    const double dot = q[0] * q0[0] + q[1] * q0[1] + q[2] * q0[2] + q[3] * q0[3];
    // finite and non-zero quaternions (their angles are finite), within the turn
    return squared_norm > 0 && squared_norm < HUGE_VAL && start_norm > 0 && start_norm < HUGE_VAL &&
           dot * dot >= kNearTurnHalfCosSquared * squared_norm * start_norm;
}

namespace {

constexpr double kMaxAcceleration = 1e100;  // [m/s^2, rad/s^2]
// A root of the pitch function is a crossing of +-90 degrees where |cos(pitch)| is below this
// (the integrators locate roots to about 1e-12 s of the step; at 1e3 rad/s that is 1e-9 rad).
constexpr double kCrossingCos = 1e-3;
constexpr int kMaxRoots = 64;  // roots that are no crossing, per communication step

// dy/dt: p_dot = v, e_dot = 1/2 (0, omega) * e (world-frame omega), (v, omega)_dot from the
// reduced equations. 1 (recoverable: CVODE retries a shorter step) for a degenerate leg.
int state_rate(double tau, const double *y, double *y_dot, void *user) {
    IntegratorImpl &im = *static_cast<IntegratorImpl *>(user);
    im.last_tau = -1;  // im.evaluation is overwritten below, even by an evaluation refused
    const Motion m = motion_of_state(y);
    double force[STEWART_LEGS];
    im.forces->at(tau, force);
    im.evaluation.winding_current = im.n > kStates ? y + kStates : nullptr;
    // the massless equations written out (plant_massless.cpp; twist_rate's for the massless model)
    bool defined;
    if (im.model->with_legs || im.model->drives.input != STEWART_PLANT_INPUT_FORCE) {
        im.evaluation.keep_terms = tau == im.forces->h;  // the step's end: its outputs reuse them
        defined = twist_rate(*im.model, m, force, im.evaluation);
    } else {
        defined = massless_twist_rate(*im.model, m, force, im.evaluation);
    }
    if (!defined) {
        im.fault = im.evaluation.fault;
        im.fault_leg = im.evaluation.fault_leg;
        return 1;
    }
    const Vector6 &a = im.evaluation.twist_rate;
    // Beyond 1e100 CVODE's weighted norms overflow (and silently stop the state): out of range.
    if (!(a.cwiseAbs().maxCoeff() < kMaxAcceleration)) {
        im.non_finite = true;
        return 1;
    }
    const double w = y[3], x = y[4], yy = y[5], z = y[6];
    const double ox = y[10], oy = y[11], oz = y[12];
    for (int i = 0; i < 3; ++i) y_dot[i] = y[7 + i];
    y_dot[3] = -0.5 * (ox * x + oy * yy + oz * z);
    y_dot[4] = 0.5 * (w * ox + oy * z - oz * yy);
    y_dot[5] = 0.5 * (w * oy + oz * x - ox * z);
    y_dot[6] = 0.5 * (w * oz + ox * yy - oy * x);
    for (int i = 0; i < 6; ++i) y_dot[7 + i] = a[i];
    if (im.n > kStates) winding_rates(*im.model, force, im.evaluation, y_dot + kStates);
    im.last_tau = tau;
    if (!im.record_arguments) return 0;
    each_state(im.n, [&](int i) { im.last_y[i] = y[i]; });
    for (int k = 0; k < STEWART_LEGS; ++k) im.last_force[k] = force[k];
    return 0;
}

// state_rate for the SUNDIALS integrators.
int right_hand_side(sunrealtype tau, N_Vector y_vector, N_Vector y_dot_vector, void *user) {
    return state_rate(tau, N_VGetArrayPointer(y_vector), N_VGetArrayPointer(y_dot_vector), user);
}

// N_VLinearCombination for the 13-state vectors: the serial vector's own arithmetic in the same
// order (so the same bits), in a loop the compiler unrolls for the fixed length; the library's
// generic loop cost the massless step a fifth of its instructions.
int linear_combination(int nvec, sunrealtype *c, N_Vector *X, N_Vector z) {
    if (nvec < 3 || N_VGetLength(z) != kStates) return N_VLinearCombination_Serial(nvec, c, X, z);
    double *zd = N_VGetArrayPointer(z);
    if (X[0] == z && c[0] == 1.0) {
        for (int i = 1; i < nvec; ++i) {
            const double *xd = N_VGetArrayPointer(X[i]);
            for (int j = 0; j < kStates; ++j) zd[j] += c[i] * xd[j];
        }
        return 0;
    }
    if (X[0] == z) {
        for (int j = 0; j < kStates; ++j) zd[j] *= c[0];
    } else {
        const double *x0 = N_VGetArrayPointer(X[0]);
        for (int j = 0; j < kStates; ++j) zd[j] = c[0] * x0[j];
    }
    for (int i = 1; i < nvec; ++i) {
        const double *xd = N_VGetArrayPointer(X[i]);
        for (int j = 0; j < kStates; ++j) zd[j] += c[i] * xd[j];
    }
    return 0;
}

// cos(pitch) for a principal pitch where only its sign is read: positive (asin's range ends at
// fl(pi/2) < pi/2, whose cosine is 6.1e-17), NaN with the pitch.
double principal_cos_sign(double pitch) { return std::isnan(pitch) ? pitch : 1.0; }

// The root the integrators watch: cos of the pitch kept continuous from the reference angles
// (the start of the step, or the last root that was no crossing). The principal pitch has
// cos >= 0; where the other triple of the rotation is the nearer one, the continuous pitch is
// beyond +-90 degrees and its cos is the negative: a sign change is a crossing.
double pitch_function(const double *y, void *user) {
    const IntegratorImpl &im = *static_cast<const IntegratorImpl *>(user);
    double angles[3];
    principal_angles(y, angles);
    const double c = std::cos(angles[1]);
    return crosses_pitch_limit(im.reference_angles, angles) ? -c : c;
}

// pitch_function's sign (and NaN) without its cosine: the written-out ERK's root test reads
// nothing else (it hands a sign change to ARKODE, which locates it with pitch_function).
double pitch_sign(const double *y, void *user) {
    const IntegratorImpl &im = *static_cast<const IntegratorImpl *>(user);
    if (near_level_turn(im.start_state, im.reference_angles[1], y)) return 1.0;
    double angles[3];
    principal_angles(y, angles);
    const double c = principal_cos_sign(angles[1]);
    return crosses_pitch_limit(im.reference_angles, angles) ? -c : c;
}

// pitch_function for the SUNDIALS integrators.
int pitch_root(sunrealtype, N_Vector y_vector, sunrealtype *g, void *user) {
    g[0] = pitch_function(N_VGetArrayPointer(y_vector), user);
    return 0;
}

// Forward-difference dense Jacobian of the right-hand side, into preallocated vectors (CVODE's
// own difference quotient allocates a vector per evaluation).
int dense_jacobian(sunrealtype t, N_Vector y, N_Vector f, SUNMatrix J, void *user,
                   N_Vector perturbed, N_Vector f_perturbed, N_Vector) {
    const double *yv = N_VGetArrayPointer(y), *fv = N_VGetArrayPointer(f);
    double *yp = N_VGetArrayPointer(perturbed);
    const double *fp = N_VGetArrayPointer(f_perturbed);
    const int n = static_cast<int>(N_VGetLength(y));
    for (int i = 0; i < n; ++i) yp[i] = yv[i];
    const double root_eps = 1.4901161193847656e-08;  // sqrt(2^-52)
    for (int j = 0; j < n; ++j) {
        const double increment = root_eps * std::max(std::fabs(yv[j]), 1e-3);
        yp[j] = yv[j] + increment;
        const int flag = right_hand_side(t, perturbed, f_perturbed, user);
        yp[j] = yv[j];
        if (flag != 0) return flag;
        double *column = SUNDenseMatrix_Column(J, j);
        for (int i = 0; i < n; ++i) column[i] = (fp[i] - fv[i]) / increment;
    }
    return 0;
}

void error_handler(int code, const char *module, const char *function, char *text, void *user) {
    IntegratorImpl &im = *static_cast<IntegratorImpl *>(user);
    std::snprintf(im.cvode_message, sizeof im.cvode_message, "%s %s (%d): %s", module, function,
                  code, text);
}

// CVODE's and ARKODE's flag names (they share the values; CVodeGetReturnFlagName allocates,
// which a step must not).
const char *flag_name(int flag) {
    switch (flag) {
        case CV_TOO_MUCH_WORK: return "TOO_MUCH_WORK (max_internal_steps reached)";
        case CV_TOO_MUCH_ACC: return "TOO_MUCH_ACC";
        case CV_ERR_FAILURE: return "ERR_FAILURE (error test failed repeatedly)";
        case CV_CONV_FAILURE: return "CONV_FAILURE (corrector did not converge)";
        case CV_LSETUP_FAIL: return "LSETUP_FAIL";
        case CV_LSOLVE_FAIL: return "LSOLVE_FAIL";
        case CV_RHSFUNC_FAIL: return "RHSFUNC_FAIL";
        case CV_FIRST_RHSFUNC_ERR: return "FIRST_RHSFUNC_ERR";
        case CV_REPTD_RHSFUNC_ERR: return "REPTD_RHSFUNC_ERR";
        case CV_UNREC_RHSFUNC_ERR: return "UNREC_RHSFUNC_ERR";
        case CV_MEM_FAIL: return "MEM_FAIL";
        case CV_ILL_INPUT: return "ILL_INPUT";
        case CV_NLS_FAIL: return "NLS_FAIL";
    }
    return "an error flag";
}

const char *fault_text(LegFault f) {
    switch (f) {
        case LegFault::ZeroLength: return "reaches zero length";
        case LegFault::LockedBaseCardan: return "lies along its base Cardan's arm (locked Cardan)";
        case LegFault::LockedPlatformCardan:
            return "lies along its platform Cardan's arm (locked Cardan)";
        case LegFault::None: break;
    }
    return "";
}

// The leg that a failed step was driving toward zero length: the shortest leg at the last
// internal step if it is below 1 % of its length at the start of the step, else -1.
int collapsing_leg(const DynamicsModel &model, const double start[kStates],
                   const double reached[kStates], double &length) {
    const Motion a = motion_of_state(start), b = motion_of_state(reached);
    int leg = -1;
    double worst = 0.01;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Vec3 &base = model.legs.base_points.col(k), &arm = model.legs.platform_points.col(k);
        const double before = (a.position + a.rotation * arm - base).norm();
        const double after = (b.position + b.rotation * arm - base).norm();
        if (after < worst * before) worst = after / before, leg = k, length = after;
    }
    return leg;
}

// The state vector SUNDIALS integrates (the platform at rest at the origin until a step sets
// it), with fused vector operations and the 13-state linear combination.
bool make_state_vector(IntegratorImpl &im, char *msg, size_t size) {
    im.context = mbs::sundials::make_context();
    if (im.context) im.y_holder.reset(N_VNew_Serial(im.n, im.context.get()));
    im.y = im.y_holder.get();
    if (!im.y)
        return set_message(msg, size, STEWART_ERR_MEMORY, "SUNDIALS context or vector failed"),
               false;
    // Fused vector operations: one loop per linear combination in the Runge-Kutta stages.
    if (N_VEnableFusedOps_Serial(im.y, SUNTRUE) != 0)
        return set_message(msg, size, STEWART_ERR_MEMORY, "N_VEnableFusedOps_Serial failed"), false;
    im.y->ops->nvlinearcombination = linear_combination;  // clones copy the operations
    N_VConst(0.0, im.y);
    NV_Ith_S(im.y, 3) = 1.0;
    return true;
}

// ARKODE's ERKStep for STEWART_PLANT_ERK (ERK 4(3); written out when written_out) and
// STEWART_PLANT_ERK5.
bool init_arkode(IntegratorImpl &im, const stewart_plant_options &o, bool written_out, char *msg,
                 size_t size) {
    im.arkode_holder.reset(ERKStepCreate(right_hand_side, 0.0, im.y, im.context.get()));
    im.arkode = im.arkode_holder.get();
    im.erk_order = o.method == STEWART_PLANT_ERK ? 4 : 5;
    im.fixed_steps = o.fixed_steps;
    im.max_internal_steps = o.max_internal_steps;
    im.relative_tolerance = o.relative_tolerance;
    im.absolute_tolerance = o.absolute_tolerance;
    im.by_hand = written_out && o.method == STEWART_PLANT_ERK &&
                 load_erk_table(ARKODE_ZONNEVELD_5_3_4, im.table);
    if (!im.arkode)
        return set_message(msg, size, STEWART_ERR_MEMORY, "ERKStepCreate failed"), false;
    int flag;
    if ((flag = ERKStepSetErrHandlerFn(im.arkode, error_handler, &im)) != ARK_SUCCESS ||
        (flag = ERKStepSetUserData(im.arkode, &im)) != ARK_SUCCESS ||
        (flag = ERKStepSetTableNum(im.arkode, o.method == STEWART_PLANT_ERK
                                                  ? ARKODE_ZONNEVELD_5_3_4
                                                  : ARKODE_DORMAND_PRINCE_7_4_5)) != ARK_SUCCESS ||
        (flag = ERKStepSStolerances(im.arkode, o.relative_tolerance, o.absolute_tolerance)) !=
            ARK_SUCCESS ||
        (flag = ERKStepSetMaxNumSteps(im.arkode, o.max_internal_steps)) != ARK_SUCCESS ||
        (flag = ERKStepRootInit(im.arkode, 1, pitch_root)) != ARK_SUCCESS ||
        (flag = ERKStepSetNoInactiveRootWarn(im.arkode)) != ARK_SUCCESS)
        return set_message(msg, size, STEWART_ERR_MEMORY, "ARKODE setup failed with %s: %s",
                           flag_name(flag), im.cvode_message),
               false;
    return true;
}

// CVODE: BDF with a dense Newton solve, or Adams with fixed-point iteration.
bool init_cvode(IntegratorImpl &im, const stewart_plant_options &o, char *msg, size_t size) {
    const bool bdf = o.method == STEWART_PLANT_BDF;
    im.cvode_holder.reset(CVodeCreate(bdf ? CV_BDF : CV_ADAMS, im.context.get()));
    im.cvode = im.cvode_holder.get();
    if (!im.cvode) return set_message(msg, size, STEWART_ERR_MEMORY, "CVodeCreate failed"), false;
    int flag;
    if ((flag = CVodeSetErrHandlerFn(im.cvode, error_handler, &im)) != CV_SUCCESS ||
        (flag = CVodeInit(im.cvode, right_hand_side, 0.0, im.y)) != CV_SUCCESS ||
        (flag = CVodeSetUserData(im.cvode, &im)) != CV_SUCCESS ||
        (flag = CVodeSStolerances(im.cvode, o.relative_tolerance, o.absolute_tolerance)) !=
            CV_SUCCESS ||
        (flag = CVodeSetMaxNumSteps(im.cvode, o.max_internal_steps)) != CV_SUCCESS ||
        (flag = CVodeRootInit(im.cvode, 1, pitch_root)) != CV_SUCCESS ||
        (flag = CVodeSetNoInactiveRootWarn(im.cvode)) != CV_SUCCESS)
        return set_message(msg, size, STEWART_ERR_MEMORY, "CVODE setup failed with %s: %s",
                           flag_name(flag), im.cvode_message),
               false;
    if (bdf) {
        im.matrix.reset(SUNDenseMatrix(im.n, im.n, im.context.get()));
        if (im.matrix) im.linear.reset(SUNLinSol_Dense(im.y, im.matrix.get(), im.context.get()));
        if (!im.linear ||
            (flag = CVodeSetLinearSolver(im.cvode, im.linear.get(), im.matrix.get())) !=
                CVLS_SUCCESS ||
            (flag = CVodeSetJacFn(im.cvode, dense_jacobian)) != CVLS_SUCCESS)
            return set_message(msg, size, STEWART_ERR_MEMORY,
                               "CVODE dense linear solver setup failed"),
                   false;
    } else {
        im.nonlinear.reset(SUNNonlinSol_FixedPoint(im.y, 0, im.context.get()));
        if (!im.nonlinear ||
            (flag = CVodeSetNonlinearSolver(im.cvode, im.nonlinear.get())) != CV_SUCCESS)
            return set_message(msg, size, STEWART_ERR_MEMORY,
                               "CVODE fixed-point solver setup failed"),
                   false;
    }
    return true;
}

// How an integrator's run over the step ended: its last flag, the time reached, and whether it
// stopped at a crossing of pitch +-90 degrees (the principal angles there).
struct RunEnd {
    int flag = 0;
    sunrealtype t_reached = 0;
    bool pitch_crossed = false;
    double angles[3] = {0, 0, 0};
};

// The step's start: no fault and no end evaluation yet, y in the integrator's vector, and the
// angles the pitch root follows. The pitch root: a crossing of +-90 degrees anywhere within the
// step stops the integrator there (a root where the continuous pitch is not near 90 degrees is a
// jump of the nearest triple over a long rotation: the reference moves on and the step goes on).
void start_advance(IntegratorImpl &im, const double *y, const ForceProfile &forces,
                   const double *start_angles) {
    im.forces = &forces;
    im.fault = LegFault::None;
    im.fault_leg = -1;
    im.non_finite = false;
    im.cvode_message[0] = '\0';
    im.end_valid = false;
    im.last_start_carried = false;
    im.last_tau = -1;
    double *v = N_VGetArrayPointer(im.y);
    each_state(im.n, [&](int i) { v[i] = y[i]; });
    if (start_angles)
        for (int i = 0; i < 3; ++i) im.reference_angles[i] = start_angles[i];
    else principal_angles(y, im.reference_angles);
    each_state(im.n, [&](int i) { im.start_state[i] = y[i]; });
}

// An explicit Runge-Kutta run's first internal step. A one-step method restarts for free; the
// first step tries the size the last step would have taken next (part of the saved state, so a
// rollback repeats it exactly). Fixed steps: h / N each, no error test (ARKODE's fixed-step
// mode; the stop time cuts the last one to end at h exactly).
double first_step_size(const IntegratorImpl &im, double h, double step_hint) {
    return im.fixed_steps > 0 ? h / im.fixed_steps : step_hint > 0 && step_hint < h ? step_hint : h;
}

// ERK 4(3) by the written-out copy of ARKODE's step: the same bits, or nothing done. True when
// it took the whole step: the end state in im.y's array, the counters in stats, the next step's
// size in step_hint, and projected whether the end state's quaternion is normalised already.
// False when it handed the step back: im.y's array is y again, for ARKODE to take the step.
bool written_out_step(IntegratorImpl &im, const double *y, const ForceProfile &forces, double first,
                      stewart_plant_statistics &stats, double &step_hint, bool &projected) {
    double *v = N_VGetArrayPointer(im.y);
    ErkControl control;
    control.fixed_steps = im.fixed_steps;
    control.first_step = first;
    control.relative_tolerance = im.relative_tolerance;
    control.absolute_tolerance = im.absolute_tolerance;
    control.max_steps = im.max_internal_steps;
    control.start_rate_known = start_rate_carried(im, y, forces);
    control.project_end = im.carry_end ? normalize_quaternion : nullptr;
    im.start_carried = false;  // erk_advance overwrites work.F[0]
    im.record_arguments = false;
    const ErkResult r = erk_advance(im.table, control, im.work, forces.h, y,
                                    principal_cos_sign(im.reference_angles[1]), state_rate,
                                    pitch_sign, &im, v, im.n);
    im.record_arguments = true;
    if (!r.done) {
        im.fault = LegFault::None;  // ARKODE repeats the step and says what failed
        im.fault_leg = -1;
        im.non_finite = false;
        im.last_tau = -1;
        for (int i = 0; i < im.n; ++i) v[i] = y[i];
        return false;
    }
    // a step done ends with the evaluation at (its end time, work.yn, the forces there: the end
    // forces exactly when that time is h)
    each_state(im.n, [&](int i) { im.last_y[i] = im.work.yn[i]; });
    if (im.last_tau == forces.h)  // what at(h) returns, without the call
        for (int k = 0; k < STEWART_LEGS; ++k) im.last_force[k] = forces.end[k];
    else if (im.last_tau >= 0) forces.at(im.last_tau, im.last_force);
    stats.steps = r.steps;
    stats.rhs_evaluations = r.rhs_evaluations;
    stats.error_test_failures = r.error_test_failures;
    stats.last_step_size = r.last_step;
    stats.last_order = im.erk_order;
    step_hint = r.next_step;
    im.last_start_carried = control.start_rate_known;
    if (r.end_projected) {
        im.start_carried = true;
        forces.at(forces.h, im.carried_force);
    }
    projected = r.end_projected;
    return true;
}

// Runs an integrator (evolve(&t_reached) returns its flag) to the step's end, on past the pitch
// function's roots that are no crossing (each moves the reference angles on).
template <class Evolve>
void evolve_past_roots(IntegratorImpl &im, int root_return, Evolve evolve, RunEnd &end) {
    const double *v = N_VGetArrayPointer(im.y);
    int roots = 0;
    do {
        end.flag = evolve(&end.t_reached);
        if (end.flag != root_return) break;
        principal_angles(v, end.angles);
        end.pitch_crossed = std::fabs(std::cos(end.angles[1])) < kCrossingCos;
        for (int i = 0; i < 3; ++i) im.reference_angles[i] = end.angles[i];
    } while (!end.pitch_crossed && ++roots < kMaxRoots);
}

// ARKODE's ERKStep over [0, h] from im.y (restarted there): its counters into stats, the step
// it would take next into step_hint.
stewart_status run_arkode(IntegratorImpl &im, double h, double first, RunEnd &end,
                          stewart_plant_statistics &stats, double &step_hint, char *msg,
                          size_t size) {
    int flag;
    if ((flag = ERKStepReInit(im.arkode, right_hand_side, 0.0, im.y)) != ARK_SUCCESS ||
        (flag = ERKStepSetStopTime(im.arkode, h)) != ARK_SUCCESS ||
        (flag = im.fixed_steps > 0 ? ERKStepSetFixedStep(im.arkode, first)
                                   : ERKStepSetInitStep(im.arkode, first)) != ARK_SUCCESS)
        return set_message(msg, size, STEWART_ERR_NOT_CONVERGED, "ARKODE restart failed: %s %s",
                           flag_name(flag), im.cvode_message);
    evolve_past_roots(
        im, ARK_ROOT_RETURN,
        [&](sunrealtype *t_reached) {
            return ERKStepEvolve(im.arkode, h, im.y, t_reached, ARK_NORMAL);
        },
        end);
    long n;
    if (ERKStepGetNumSteps(im.arkode, &n) == ARK_SUCCESS) stats.steps = n;
    if (ERKStepGetNumErrTestFails(im.arkode, &n) == ARK_SUCCESS) stats.error_test_failures = n;
    long explicit_evals = 0;
    if (ERKStepGetNumRhsEvals(im.arkode, &explicit_evals) == ARK_SUCCESS)
        stats.rhs_evaluations = explicit_evals;
    sunrealtype h_last = 0, h_next = 0;
    if (ERKStepGetLastStep(im.arkode, &h_last) == ARK_SUCCESS) stats.last_step_size = h_last;
    if (ERKStepGetCurrentStep(im.arkode, &h_next) == ARK_SUCCESS && end.flag >= 0)
        step_hint = h_next;
    stats.last_order = im.erk_order;
    return STEWART_OK;
}

// CVODE over [0, h] from im.y (restarted there): its counters into stats.
stewart_status run_cvode(IntegratorImpl &im, double h, RunEnd &end, stewart_plant_statistics &stats,
                         char *msg, size_t size) {
    int flag;
    if ((flag = CVodeReInit(im.cvode, 0.0, im.y)) != CV_SUCCESS ||
        (flag = CVodeSetStopTime(im.cvode, h)) != CV_SUCCESS)
        return set_message(msg, size, STEWART_ERR_NOT_CONVERGED, "CVODE restart failed: %s %s",
                           flag_name(flag), im.cvode_message);
    evolve_past_roots(
        im, CV_ROOT_RETURN,
        [&](sunrealtype *t_reached) { return CVode(im.cvode, h, im.y, t_reached, CV_NORMAL); },
        end);
    long n;
    if (CVodeGetNumSteps(im.cvode, &n) == CV_SUCCESS) stats.steps = n;
    if (CVodeGetNumRhsEvals(im.cvode, &n) == CV_SUCCESS) stats.rhs_evaluations = n;
    if (CVodeGetNumNonlinSolvIters(im.cvode, &n) == CV_SUCCESS) stats.nonlinear_iterations = n;
    if (CVodeGetNumErrTestFails(im.cvode, &n) == CV_SUCCESS) stats.error_test_failures = n;
    if (im.linear && CVodeGetNumJacEvals(im.cvode, &n) == CVLS_SUCCESS)
        stats.jacobian_evaluations = n;
    int order = 0;
    sunrealtype h_last = 0;
    if (CVodeGetLastOrder(im.cvode, &order) == CV_SUCCESS) stats.last_order = order;
    if (CVodeGetLastStep(im.cvode, &h_last) == CV_SUCCESS) stats.last_step_size = h_last;
    return STEWART_OK;
}

// Why a run from y did not take the whole step [0, h] (STEWART_OK when it did): a crossing of
// pitch +-90 degrees, a leg driven toward zero length, a singular pose, accelerations out of
// range, or the integrator's own failure or stop short of h.
stewart_status run_failure(const IntegratorImpl &im, const double *y, double h, const RunEnd &end,
                           char *msg, size_t size) {
    const double *v = N_VGetArrayPointer(im.y);
    const char *module = im.arkode ? "ARKODE" : "CVODE";
    const double t_reached = static_cast<double>(end.t_reached);
    if (end.pitch_crossed)
        return set_message(msg, size, STEWART_ERR_SINGULAR,
                           "the motion takes pitch through +-90 degrees near t + %g s (pitch = %g "
                           "rad there), where roll and yaw are undefined",
                           t_reached, end.angles[1]);
    // kMaxRoots jumps of the triple
    const int flag = end.flag == CV_ROOT_RETURN ? CV_TOO_MUCH_WORK : end.flag;
    if (flag < 0 || end.t_reached != h) {
        double length = 0;
        const int leg = collapsing_leg(*im.model, y, v, length);
        if (leg >= 0)
            return set_message(msg, size, STEWART_ERR_UNREACHABLE,
                               "unreachable, leg %d: the motion drives it toward zero length "
                               "(%.3g m near t + %g s)",
                               leg + 1, length, t_reached);
    }
    if (flag < 0) {
        if (im.fault != LegFault::None)
            return set_message(msg, size,
                               im.fault == LegFault::ZeroLength ? STEWART_ERR_UNREACHABLE
                                                                : STEWART_ERR_SINGULAR,
                               "the motion reaches a singular pose near t + %g s: leg %d %s",
                               t_reached, im.fault_leg + 1, fault_text(im.fault));
        if (im.non_finite)
            return set_message(msg, size, STEWART_ERR_NOT_CONVERGED,
                               "the accelerations are not finite or above 1e100 near t + %g s "
                               "(forces or motion out of range)",
                               t_reached);
        if (im.arkode && im.model->drives.inductive) {  // the usual cause, and its cure
            double tau = HUGE_VAL;
            for (const LegDrive &d : im.model->drives.legs)
                if (d.inductance > 0) tau = std::min(tau, d.inductance / d.resistance);
            // first, so that a caller's longer prefix leaves it whole
            return set_message(msg, size, STEWART_ERR_NOT_CONVERGED,
                               "stiff windings (L/R = %g s: take method = bdf): %s failed at t + "
                               "%g s with %s: %s",
                               tau, module, t_reached, flag_name(flag), im.cvode_message);
        }
        return set_message(msg, size, STEWART_ERR_NOT_CONVERGED,
                           "%s failed at t + %g s with %s: %s", module, t_reached, flag_name(flag),
                           im.cvode_message);
    }
    // a solver's success short of the end would be a step not taken (found with a saved step
    // hint of 4.9e-324 s)
    if (end.t_reached != h)
        return set_message(msg, size, STEWART_ERR_NOT_CONVERGED,
                           "%s stopped at t + %g s, short of the step's end h = %g s", module,
                           t_reached, h);
    return STEWART_OK;
}

}  // namespace

Integrator::~Integrator() { delete impl_; }

bool Integrator::init(const DynamicsModel *model, const stewart_plant_options &o, char *msg,
                      size_t size, bool written_out, bool carry_end) {
    impl_ = new (std::nothrow) IntegratorImpl;
    if (!impl_) return set_message(msg, size, STEWART_ERR_MEMORY, "out of memory"), false;
    IntegratorImpl &im = *impl_;
    im.model = model;
    im.n = state_count(*model);
    im.carry_end = carry_end;
    im.evaluation.fill_legs = false;  // massless: nothing reads its legs (end_evaluation())
    if (!make_state_vector(im, msg, size)) return false;
    return o.method == STEWART_PLANT_ERK || o.method == STEWART_PLANT_ERK5
               ? init_arkode(im, o, written_out, msg, size)
               : init_cvode(im, o, msg, size);
}

stewart_status Integrator::advance(double *y, const ForceProfile &forces, double &step_hint,
                                   char *msg, size_t size, const double *start_angles) {
    IntegratorImpl &im = *impl_;
    start_advance(im, y, forces, start_angles);
    stats_ = stewart_plant_statistics{};
    RunEnd end;
    stewart_status s;
    if (im.arkode) {
        const double first = first_step_size(im, forces.h, step_hint);
        bool projected = false;
        if (im.by_hand && written_out_step(im, y, forces, first, stats_, step_hint, projected))
            return finish_step(y, forces.h, msg, size, projected);
        s = run_arkode(im, forces.h, first, end, stats_, step_hint, msg, size);
    } else {
        s = run_cvode(im, forces.h, end, stats_, msg, size);
    }
    if (s == STEWART_OK) s = run_failure(im, y, forces.h, end, msg, size);
    return s == STEWART_OK ? finish_step(y, forces.h, msg, size) : s;
}

stewart_status Integrator::finish_step(double *y, double h, char *msg, size_t size,
                                       bool normalized) {
    IntegratorImpl &im = *impl_;
    const double *v = N_VGetArrayPointer(im.y);
    const ForceProfile &forces = *im.forces;
    // Whether the last evaluation was at exactly the state returned, the end time and forces.
    // (each test in one pass without a branch per value)
    bool same = im.last_tau == h;
    each_state(im.n, [&](int i) { same &= im.last_y[i] == v[i]; });
    for (int k = 0; k < STEWART_LEGS; ++k) same &= im.last_force[k] == forces.end[k];
    im.end_valid = same;
    double out[kMaxStates];
    each_state(im.n, [&](int i) { out[i] = v[i]; });
    if (!normalized) normalize_quaternion(out);
    double zero_if_finite = 0;  // the sum of x * 0: NaN exactly when some x is not finite
    each_state(im.n, [&](int i) { zero_if_finite += out[i] * 0.0; });
    if (zero_if_finite != 0)
        for (int i = 0; i < im.n; ++i)
            if (!std::isfinite(out[i]))
                return set_message(msg, size, STEWART_ERR_NOT_CONVERGED,
                                   "the state is not finite after the step (state %d)", i);
    each_state(im.n, [&](int i) { y[i] = out[i]; });
    return STEWART_OK;
}

bool Integrator::start_carried() const { return impl_ && impl_->last_start_carried; }

const Evaluation *Integrator::end_evaluation() const {
    return impl_ && impl_->end_valid ? &impl_->evaluation : nullptr;
}

}  // namespace plant
}  // namespace stewart
