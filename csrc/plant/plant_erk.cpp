// ARKODE 6.4's ERKStep, step by step (arkInitialSetup, arkEvolve, erkStep_TakeStep,
// erkStep_ComputeSolutions, arkCheckTemporalError, arkAdapt with the PI controller ERKStep sets,
// arkCompleteStep, arkRootCheck3, arkGetDky with the cubic Hermite interpolant): each linear
// combination below is the vector operation ARKODE calls there, with its operands in ARKODE's
// order, and each scalar formula is ARKODE's, so every rounding is the same.
#include "plant/plant_erk.hpp"

#include <cstdio>  // arkode_butcher.h uses FILE without including it

#include <arkode/arkode_butcher_erk.h>

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace stewart {
namespace plant {

namespace {

constexpr double kUnitRoundoff = DBL_EPSILON;                // SUNDIALS' UNIT_ROUNDOFF for double
constexpr double kFuzzFactor = 100.0;                        // FUZZ_FACTOR
constexpr double kOneMinus = 0.999999, kOnePlus = 1.000001;  // ONEMSM, ONEPSM
constexpr double kTiny = 1e-10;                              // TINY
// ERKStep's step-size control: ERKStepSetDefaults over arkSetDefaults (arkode_adapt_impl.h)
constexpr double kBias = 1.2, kSafety = 0.99, kGrowth = 25.0, kPiK1 = 0.8, kPiK2 = 0.31;
constexpr double kEtaFirst = 10000.0, kEtaErrorFail = 0.3, kEtaMin = 0.1, kCfl = 0.5;
constexpr double kFixedLower = 1.0, kFixedUpper = 1.5;  // no change of h within these ratios
constexpr int kSmallErrorFails = 2, kMaxErrorFails = 7;

// z = c[0] x[0] + c[1] x[1] + ... (left to right), then + y if given: N_VLinearCombination with
// a last vector y at coefficient 1, as ERKStep forms stages and solutions (the serial vector's
// loop for three or more vectors; for two it is N_VLinearSum's a x + y, the same operations).
// Each element's sum in one pass, unrolled for the count (the same operations in the same order
// as the vector's loops over z, at half the instructions).
template <int N, int Count, bool WithY>
void combine_fixed(const double *c, const double (*x)[kMaxStates], const double *y, double *z) {
    for (int j = 0; j < N; ++j) {
        double sum = c[0] * x[0][j];
#pragma GCC unroll 5
        for (int i = 1; i < Count; ++i) sum += c[i] * x[i][j];
        if (WithY) sum += 1.0 * y[j];
        z[j] = sum;
    }
}

template <int N, int Count>
void combine_count(const double *c, const double (*x)[kMaxStates], const double *y, double *z) {
    if (y) combine_fixed<N, Count, true>(c, x, y, z);
    else combine_fixed<N, Count, false>(c, x, y, z);
}

template <int N>
void combine(int count, const double *c, const double (*x)[kMaxStates], const double *y,
             double *z) {
    static_assert(kMaxErkStages == 5, "combine unrolls up to five stages");
    switch (count) {
        case 1: return combine_count<N, 1>(c, x, y, z);
        case 2: return combine_count<N, 2>(c, x, y, z);
        case 3: return combine_count<N, 3>(c, x, y, z);
        case 4: return combine_count<N, 4>(c, x, y, z);
        default: return combine_count<N, 5>(c, x, y, z);
    }
}

// arkEwtSetSS: 1 / (rtol |y| + atol).
template <int N>
void error_weights(const ErkControl &control, const double *y, double *w) {
    for (int j = 0; j < N; ++j)
        w[j] = 1.0 / (control.relative_tolerance * std::fabs(y[j]) + control.absolute_tolerance);
}

// N_VWrmsNorm_Serial.
template <int N>
double wrms_norm(const double *x, const double *w) {
    double sum = 0;
    for (int j = 0; j < N; ++j) {
        const double p = x[j] * w[j];
        sum += p * p;
    }
    const double mean = sum / N;
    return mean <= 0 ? 0.0 : std::sqrt(mean);
}

// SUNRpowerR. pow(1, y) is 1 exactly (IEEE 754, C99 F.9.4.4), the error history's value at the
// first step of every communication step: then no call.
double power(double base, double exponent) {
    return base <= 0 ? 0.0 : base == 1.0 ? 1.0 : std::pow(base, exponent);
}

// The step-size ratio arkAdapt proposes after a step of h with error dsm (ERKStep's PI
// controller, no stability limit, no hmin or hmax).
double adapt_ratio(const ErkTable &table, double h, double dsm, double error_history,
                   double eta_max) {
    const double ecur = kBias * dsm;
    const double k1 = -kPiK1 / table.embedding_order, k2 = kPiK2 / table.embedding_order;
    const double e1 = std::max(ecur, kTiny), e2 = std::max(error_history, kTiny);
    double h_acc = h * power(e1, k1) * power(e2, k2);
    const double direction = h / std::fabs(h);
    double h_cfl = 1.0e30 * std::fabs(h);  // arkExpStab gives 0: no stability limit
    h_acc *= kSafety;
    h_cfl *= kCfl * direction;
    h_acc = direction * std::min(std::fabs(h_acc), std::fabs(eta_max * h));
    h_acc = direction * std::max(std::fabs(h_acc), std::fabs(kEtaMin * h));
    h_acc = direction * std::min(std::fabs(h_acc), std::fabs(h_cfl));
    if (dsm <= 1.0 && std::fabs(h_acc) > std::fabs(h * kFixedLower * kOneMinus) &&
        std::fabs(h_acc) < std::fabs(h * kFixedUpper * kOnePlus))
        h_acc = h;
    double eta = h_acc / h;
    eta = std::max(eta, 0.0 / std::fabs(h));         // hmin = 0
    eta /= std::max(1.0, std::fabs(h) * 0.0 * eta);  // hmax_inv = 0
    return eta;
}

}  // namespace

bool load_erk_table(int table_number, ErkTable &table) {
    ARKodeButcherTable B = ARKodeButcherTable_LoadERK(static_cast<ARKODE_ERKTableID>(table_number));
    if (!B) return false;
    const bool fits = B->stages >= 2 && B->stages <= kMaxErkStages && B->d && B->p > 0 &&
                      std::fabs(B->c[B->stages - 1] - 1.0) > 1e-14;  // erkStep_FullRHS's TINY
    if (fits) {
        table.stages = B->stages;
        table.embedding_order = B->p;
        for (int i = 0; i < B->stages; ++i) {
            table.b[i] = B->b[i];
            table.d[i] = B->d[i];
            table.c[i] = B->c[i];
            for (int j = 0; j < B->stages; ++j) table.A[i][j] = B->A[i][j];
        }
    }
    ARKodeButcherTable_Free(B);
    return fits;
}

namespace {

// The step-size controller between internal steps (arkEvolve's): the time reached, the step to
// take, its ratio to the last, the step the last one proposed, the bound on the ratio, and the
// last step's error (its estimate's norm with the controller's bias).
struct StepController {
    double tn = 0, h = 0, eta = 1.0, h_prime = 0, eta_max = kEtaFirst, error_history = 1.0;
};

// erkStep_TakeStep and erkStep_ComputeSolutions: stages 1..s-1 of the step h from (tn, w.yn),
// the solution in w.ycur and, adaptive only, the WRMS norm of the error estimate in dsm. False
// if the right-hand side refused a stage.
template <int N>
bool stages_and_solution(const ErkTable &table, bool fixed, ErkWork &w, double tn, double h,
                         ErkRhs rhs, void *user, ErkResult &r, double &dsm) {
    const int s = table.stages;
    double c[kMaxErkStages] = {0};  // (every coefficient read is set: GCC cannot see it)
    for (int is = 1; is < s; ++is) {
        const double t_stage = tn + table.c[is] * h;
        for (int js = 0; js < is; ++js) c[js] = h * table.A[is][js];
        combine<N>(is, c, w.F, w.yn, w.ycur);
        if (rhs(t_stage, w.ycur, w.F[is], user) != 0) return false;
        ++r.rhs_evaluations;
    }
    for (int j = 0; j < s; ++j) c[j] = h * table.b[j];
    combine<N>(s, c, w.F, w.yn, w.ycur);
    if (fixed) return true;  // arkEvolve: eta = 1, no error test
    for (int j = 0; j < s; ++j) c[j] = h * (table.b[j] - table.d[j]);
    combine<N>(s, c, w.F, nullptr, w.error);
    dsm = wrms_norm<N>(w.error, w.weight);
    return true;
}

// One internal step tried until it passes the error test (adaptive; each failure shrinks k.h),
// with the ratio of the next step in k.eta. False when the right-hand side refused a stage or
// the test failed kMaxErrorFails times (ARK_ERR_FAILURE): ARKODE's to repeat.
template <int N>
bool step_passing_error_test(const ErkTable &table, bool fixed, ErkWork &w, StepController &k,
                             ErkRhs rhs, void *user, ErkResult &r, double &dsm) {
    for (int error_fails = 0;;) {
        if (!stages_and_solution<N>(table, fixed, w, k.tn, k.h, rhs, user, r, dsm)) return false;
        if (fixed) return true;
        // arkCheckTemporalError, then arkEvolve's bounds on eta
        k.eta = adapt_ratio(table, k.h, dsm, k.error_history, k.eta_max);
        if (!(dsm <= 1.0)) {  // ARKODE's test: a NaN estimate fails too
            ++r.error_test_failures;
            if (++error_fails == kMaxErrorFails) return false;  // ARK_ERR_FAILURE
            k.eta_max = 1.0;
            if (error_fails >= kSmallErrorFails) k.eta = std::min(k.eta, kEtaErrorFail);
        }
        k.eta = std::min(k.eta, k.eta_max);
        k.eta = std::max(k.eta, 0.0 / std::fabs(k.h));
        k.eta /= std::max(1.0, std::fabs(k.h) * 0.0 * k.eta);
        if (dsm <= 1.0) return true;
        k.h *= k.eta;
        k.h_prime = k.h;
    }
}

// arkCompleteStep: the step's end time t_cur, snapped to the stop time within roundoff; the
// interpolant keeps the step's start; the end evaluation (the last stage is not at the end) at
// the new state, which becomes w.yn. False when the root function or the right-hand side
// refuses the new state: ARKODE's to repeat.
template <int N>
bool complete_step(const ErkControl &control, ErkWork &w, const StepController &k, double t_stop,
                   ErkRhs rhs, ErkRoot root, void *user, ErkResult &r, double &t_cur,
                   double &roundoff) {
    t_cur = k.tn + k.h;
    roundoff = kFuzzFactor * kUnitRoundoff * (std::fabs(t_cur) + std::fabs(k.h));
    if (std::fabs(t_cur - t_stop) <= roundoff) t_cur = t_stop;
    for (int j = 0; j < N; ++j) {
        w.yold[j] = w.yn[j];
        w.fold[j] = w.F[0][j];
    }
    // arkRootCheck3 (below in ARKODE, on the same values: a refusal of either hands the
    // step back) before the projection, so that it decides on ARKODE's state
    if (!(root(w.ycur, user) > 0)) return false;
    if (control.project_end && t_cur == t_stop) {  // the last step: y_out will be yn
        control.project_end(w.ycur);
        r.end_projected = true;
    }
    if (rhs(t_cur, w.ycur, w.F[0], user) != 0) return false;
    ++r.rhs_evaluations;
    for (int j = 0; j < N; ++j) w.yn[j] = w.ycur[j];
    return true;
}

// arkGetDky(t_out): the cubic Hermite interpolant between the last step's ends (h, ending at
// tn) (a = (0, 1, 0, 0) at tout = tcur), as N_VLinearCombination of (yold, ynew, fold, fnew).
template <int N>
void interpolate(const ErkWork &w, double t_out, double tn, double h, double *y_out) {
    const double tau = (t_out - tn) / h, tau2 = tau * tau, tau3 = tau * tau2;
    const double a0 = 3.0 * tau2 + 2.0 * tau3, a1 = 1.0 - 3.0 * tau2 - 2.0 * tau3,
                 a2 = h * (tau2 + tau3), a3 = h * (tau + 2.0 * tau2 + tau3);
    for (int j = 0; j < N; ++j) {
        double z = a0 * w.yold[j];
        z += a1 * w.yn[j];
        z += a2 * w.fold[j];
        z += a3 * w.F[0][j];
        y_out[j] = z;
    }
}

template <int N>
ErkResult advance_states(const ErkTable &table, const ErkControl &control, ErkWork &w,
                         double h_comm, const double *y0, double g_start, ErkRhs rhs, ErkRoot root,
                         void *user, double *y_out) {
    ErkResult r;
    const bool fixed = control.fixed_steps > 0;
    const double h_in = fixed ? h_comm / control.fixed_steps : control.first_step;
    // arkRootCheck1: a zero of g at the start is ARKODE's to handle.
    if (!(g_start > 0) || !(h_in > 0)) return r;
    const double t_stop = h_comm, t_out = h_comm, stop_factor = 1.0 - 4.0 * kUnitRoundoff;
    for (int j = 0; j < N; ++j) w.yn[j] = y0[j];
    // arkInitialSetup: the full right-hand side at the start into F[0] (and fn, the same
    // values); the first step, limited so as not to overtake the stop time
    if (!control.start_rate_known && rhs(0.0, w.yn, w.F[0], user) != 0) return r;
    ++r.rhs_evaluations;  // ARKODE's count, made or carried (so a rollback repeats the count)
    StepController k;
    k.h = h_in;
    if ((k.tn + k.h - t_stop) * k.h > 0) k.h = (t_stop - k.tn) * stop_factor;
    k.h_prime = k.h;
    for (;;) {
        if (r.steps >= control.max_steps) return r;  // ARK_TOO_MUCH_WORK: ARKODE says so
        if (fixed) {
            k.h = h_in;
            if ((k.tn + k.h - t_stop) * k.h > 0) k.h = (t_stop - k.tn) * stop_factor;
        } else {
            if (k.h_prime != k.h) k.h = k.h * k.eta;
            error_weights<N>(control, w.yn, w.weight);
        }
        double dsm = 0, t_cur, roundoff;
        if (!step_passing_error_test<N>(table, fixed, w, k, rhs, user, r, dsm) ||
            !complete_step<N>(control, w, k, t_stop, rhs, root, user, r, t_cur, roundoff))
            return r;
        k.error_history = dsm * kBias;
        ++r.steps;
        k.tn = t_cur;
        r.last_step = k.h;
        k.h_prime = k.h * (fixed ? 1.0 : k.eta);
        k.eta_max = kGrowth;
        // arkRootCheck3 was in complete_step: g at the new state; a sign change or zero is a
        // root, ARKODE's to locate
        if ((t_cur - t_out) * k.h >= 0) break;  // tout reached
        // the stop-time test after a step; the snap above makes its first branch unreachable
        if (std::fabs(t_cur - t_stop) <= roundoff) return r;
        if ((t_cur + k.h_prime - t_stop) * k.h > 0) {
            k.h_prime = (t_stop - t_cur) * stop_factor;
            k.eta = k.h_prime / k.h;
        }
        if (fixed) k.eta = 1.0;
    }
    r.next_step = k.h_prime;
    interpolate<N>(w, t_out, k.tn, k.h, y_out);
    r.done = true;
    return r;
}

}  // namespace

ErkResult erk_advance(const ErkTable &table, const ErkControl &control, ErkWork &w, double h_comm,
                      const double *y0, double g_start, ErkRhs rhs, ErkRoot root, void *user,
                      double *y_out, int states) {
    return states == kStates ? advance_states<kStates>(table, control, w, h_comm, y0, g_start, rhs,
                                                       root, user, y_out)
                             : advance_states<kMaxStates>(table, control, w, h_comm, y0, g_start,
                                                          rhs, root, user, y_out);
}

}  // namespace plant
}  // namespace stewart
