#include "forward/newton.hpp"

#include <kinsol/kinsol.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "core/published.hpp"
#include "forward/leg_pairs.hpp"
#include "util/message.hpp"

namespace stewart {

namespace {

constexpr int kN = STEWART_LEGS;  // six lengths, six pose coordinates

}  // namespace

struct ForwardNewton::Impl {
    // Freed in reverse order: KINSOL, its linear solver and matrix, the vectors, the context.
    mbs::sundials::Context context;
    mbs::sundials::Vector u, scale, f;
    mbs::sundials::Matrix matrix;
    mbs::sundials::LinearSolver linear;
    mbs::sundials::Memory<KINFree> kinsol;
    char kinsol_message[STEWART_MESSAGE_SIZE] = "";
    // What KINSOL was last told (set again only when it changes).
    double tolerance = -1;
    int max_iterations = -1;
    bool chord = false;
    // Per solve: the problem.
    const PlatformGeometry *geometry = nullptr;
    const double *target = nullptr;
    // The last residual evaluated, and the legs there; scanned: last_residual and worst_leg are
    // the cache's.
    LegsAt cache;
    double last_residual = 0;
    int worst_leg = 0;
    bool scanned = false;
    // The leg Jacobian factored at the last set-up; active: the linear solver's factors (these,
    // or the chord's, read in place).
    LegFactors factors;
    const LegFactors *active = &factors;
};

namespace {

using Impl = ForwardNewton::Impl;

// F(u) into f; returns its max-norm (INFINITY if not finite) and records the worst leg.
double evaluate_residual(Impl &im, const double *u, double *f) {
    const double *residual = im.cache.residual.data();
    // KINSOL evaluates its start again: the legs there, and their scan, are known already.
    const bool known = im.cache.valid && std::equal(u, u + 6, im.cache.q);
    if (!known) evaluate_legs(*im.geometry, u, im.target, im.cache);
    for (int k = 0; k < kN; k += 2) store_pair(f + k, load_pair(residual + k));
    if (known && im.scanned) return im.last_residual;
    // The usual case in one pass (two legs at a time): every residual finite and every leg
    // longer than min_length; then the largest |residual| (the first on ties).
    const double min_length = im.geometry->min_length;
    double size[kN];
    PairBits unusual = {0, 0};
    for (int k = 0; k < kN; k += 2) {
        const Pair magnitude = abs_pair(load_pair(residual + k));
        store_pair(size + k, magnitude);
        unusual |= ~((magnitude <= DBL_MAX) & (load_pair(im.cache.length.data() + k) > min_length));
    }
    const bool usual = !any(unusual);  // (NaN: unusual)
    double worst = 0;
    int worst_leg = 0;
    for (int k = 0; k < kN; ++k)
        if (size[k] > worst) worst = size[k], worst_leg = k;
    // A leg of (nearly) zero length has no axis: no Jacobian there. The first leg not finite or
    // too short is the worst, INFINITY.
    for (int k = 0; !usual && k < kN; ++k)
        if (!(std::fabs(f[k]) <= DBL_MAX) || !(im.cache.length[k] > min_length)) {
            worst = INFINITY, worst_leg = k;
            break;
        }
    im.worst_leg = worst_leg;
    im.last_residual = worst;
    im.scanned = true;
    return worst;
}

// KINSOL's residual callback; 1 (recoverable: KINSOL steps shorter) if not finite.
int residual_fn(N_Vector u, N_Vector f, void *user) {
    Impl &im = *static_cast<Impl *>(user);
    return std::isfinite(evaluate_residual(im, NV_DATA_S(u), NV_DATA_S(f))) ? 0 : 1;
}

// KINSOL's Jacobian callback: the legs at u (the factoring is the linear solver's set-up).
int jacobian_fn(N_Vector u, N_Vector, SUNMatrix, void *user, N_Vector, N_Vector) {
    Impl &im = *static_cast<Impl *>(user);
    const double *ud = NV_DATA_S(u);
    if (!im.cache.valid || !std::equal(ud, ud + 6, im.cache.q)) {
        evaluate_legs(*im.geometry, ud, im.target, im.cache);
        im.scanned = false;
    }
    return 0;
}

// The custom linear solver (core/kinsol_custom): the leg Jacobian at the legs of the set-up's
// iterate, factored. dL/dq = J diag(I, c E) with E the angle-rate matrix, so a solve with J then
// E^-1 / c is the Newton step in pose coordinates.
int solver_setup(SUNLinearSolver S, SUNMatrix) {
    Impl &im = *static_cast<Impl *>(S->content);
    double norm1;
    im.active = &im.factors;
    return factor_legs(*im.geometry, im.cache, im.factors, norm1) ? SUNLS_SUCCESS
                                                                  : SUNLS_LUFACT_FAIL;
}
// x = (dL/dq)^-1 b with the factors; recoverable failure (KINSOL sets up afresh if the factors
// were the chord's) at pitch +-90 deg.
int solver_solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, realtype) {
    Impl &im = *static_cast<Impl *>(S->content);
    return pose_rates_from(*im.active, im.active->trig, NV_DATA_S(b), NV_DATA_S(x))
               ? SUNLS_SUCCESS
               : SUNLS_PACKAGE_FAIL_REC;
}
}  // namespace

ForwardNewton::ForwardNewton() : impl_(new (std::nothrow) Impl) {
    if (!impl_) return;
    Impl &im = *impl_;
    im.context = mbs::sundials::make_context();
    if (!im.context) return;
    SUNContext context = im.context.get();
    im.u.reset(N_VNew_Serial(kN, context));
    // The six-entry operations (KINSOL's work vectors are clones of u: they inherit them).
    if (!im.u || !mbs::use_fixed_length_ops(im.u.get())) return;
    im.scale.reset(N_VClone(im.u.get()));
    im.f.reset(N_VClone(im.u.get()));
    if (!im.scale || !im.f) return;
    N_VConst(1.0, im.scale.get());
    SUNMatrix matrix = nullptr;
    SUNLinearSolver linear = nullptr;
    const bool made =
        mbs::make_custom_linear_solver(context, &im, solver_setup, solver_solve, matrix, linear);
    im.matrix.reset(matrix);
    im.linear.reset(linear);
    if (!made) return;
    im.kinsol.reset(KINCreate(context));
    void *kinsol = im.kinsol.get();
    if (!kinsol) return;
    // Once, not per solve: memory, linear solver, callbacks. No step-size stop (the residual
    // decides).
    ok_ = KINSetErrHandlerFn(kinsol, mbs::keep_kinsol_message, im.kinsol_message) == KIN_SUCCESS &&
          KINInit(kinsol, residual_fn, im.u.get()) == KIN_SUCCESS &&
          KINSetUserData(kinsol, &im) == KIN_SUCCESS &&
          KINSetLinearSolver(kinsol, linear, matrix) == KINLS_SUCCESS &&
          KINSetJacFn(kinsol, jacobian_fn) == KINLS_SUCCESS &&
          KINSetMaxSetupCalls(kinsol, 1) == KIN_SUCCESS &&
          KINSetNoInitSetup(kinsol, SUNFALSE) == KIN_SUCCESS &&
          KINSetScaledStepTol(kinsol, 1e-300) == KIN_SUCCESS;
}

const LegsAt &ForwardNewton::last() const { return impl_->cache; }

ForwardNewton::~ForwardNewton() { delete impl_; }

stewart_status ForwardNewton::solve(const PlatformGeometry &g, const double target[kN],
                                    double tolerance, int max_iterations, const LegFactors *chord,
                                    double drift, double q[6], NewtonStats &stats, char *msg,
                                    size_t size) {
    Impl &im = *impl_;
    im.geometry = &g;
    im.target = target;
    im.cache.valid = im.scanned = false;
    stats = NewtonStats();
    int flag = KIN_SUCCESS;
    if (tolerance != im.tolerance || max_iterations != im.max_iterations) {
        if ((flag = KINSetFuncNormTol(im.kinsol.get(), tolerance)) != KIN_SUCCESS ||
            (flag = KINSetNumMaxIters(im.kinsol.get(), max_iterations)) != KIN_SUCCESS) {
            im.tolerance = -1;
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "KINSOL rejected tolerance = %g or max_iterations = %d (flag %d)",
                               tolerance, max_iterations, flag);
        }
        im.tolerance = tolerance, im.max_iterations = max_iterations;
    }
    void *kinsol = im.kinsol.get();
    double *u = NV_DATA_S(im.u.get());
    for (int i = 0; i < 6; i += 2) store_pair(u + i, load_pair(q + i));
    // KINSOL's own first test (the start accepted if its residual is <= 0.01 tolerance), made
    // here so that a measurement that did not change costs no KINSOL set-up.
    evaluate_residual(im, u, NV_DATA_S(im.f.get()));
    long iterations = 0;
    if (im.last_residual <= 0.01 * tolerance) {
        flag = KIN_INITIAL_GUESS_OK;
    } else {
        // Chord: the first iteration with the given factors (no set-up), a fresh Jacobian every
        // second iteration after; else exact Newton, a fresh Jacobian every iteration.
        const bool use_chord = chord != nullptr && im.last_residual * drift <= tolerance;
        im.active = use_chord ? chord : &im.factors;
        if (use_chord != im.chord) {
            KINSetNoInitSetup(kinsol, use_chord ? SUNTRUE : SUNFALSE);
            KINSetMaxSetupCalls(kinsol, use_chord ? 2 : 1);
            im.chord = use_chord;
        }
        im.kinsol_message[0] = '\0';
        flag = KINSol(kinsol, im.u.get(), KIN_NONE, im.scale.get(), im.scale.get());
        const int stats_flag = KINGetNumNonlinSolvIters(kinsol, &iterations);
        if (stats_flag != KIN_SUCCESS)
            return set_message(msg, size, STEWART_ERR_NOT_CONVERGED,
                               "KINGetNumNonlinSolvIters failed with flag %d", stats_flag);
        // The residual kept is that of the last point evaluated: make it u's.
        if (!im.cache.valid || !std::equal(u, u + 6, im.cache.q))
            evaluate_residual(im, u, NV_DATA_S(im.f.get()));
    }
    stats.iterations = static_cast<int>(iterations);
    stats.residual = im.last_residual;
    stats.worst_leg = im.worst_leg;
    stats.flag = flag;
    Pair zero = {0, 0};  // (v * 0 is 0 for a finite v, NaN otherwise)
    for (int i = 0; i < 6; i += 2) zero += load_pair(u + i) * 0.0;
    const bool finite = std::isfinite(im.last_residual) && zero[0] + zero[1] == 0;
    if (finite)
        for (int i = 0; i < 6; i += 2) store_pair(q + i, load_pair(u + i));
    if (flag >= 0 && finite && im.last_residual <= tolerance) return STEWART_OK;
    if (flag == KIN_LSETUP_FAIL || flag == KIN_LINSOLV_NO_RECOVERY)
        return set_message(msg, size, STEWART_ERR_SINGULAR,
                           "the length Jacobian is singular at a Newton iterate (KINSOL flag %d "
                           "after %ld iterations)",
                           flag, iterations);
    return set_message(msg, size, STEWART_ERR_NOT_CONVERGED,
                       "Newton did not converge: leg %d is still %g m off its measured length "
                       "after %ld iterations (tolerance %g m; KINSOL flag %d%s%s)",
                       im.worst_leg + 1, im.last_residual, iterations, tolerance, flag,
                       im.kinsol_message[0] ? ": " : "", im.kinsol_message);
}

}  // namespace stewart
