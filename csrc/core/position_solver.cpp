#include "core/position_solver.hpp"

#include <kinsol/kinsol.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/assembly.hpp"
#include "core/kinsol_custom.hpp"
#include "core/message.hpp"
#include "core/sundials_holder.hpp"

using mbs::set_message;

namespace mbs {

struct PositionSolver::Impl {
    State &state;
    bool dense = false;
    // Freed in reverse order: KINSOL first, the context last.
    sundials::Context context;
    sundials::Vector u, scale, work;
    sundials::Matrix matrix;
    sundials::LinearSolver linear;
    sundials::Memory<KINFree> kinsol;
    char kinsol_message[MBS_MESSAGE_SIZE] = "";
    double last_residual = 0;  // max-norm of the last residual evaluated (INFINITY if not finite)
    bool values_at_guess = false;  // state.values hold Phi_q at state.q (the initial guess)
    explicit Impl(State &s) : state(s) {}
};

namespace {

using Impl = PositionSolver::Impl;

// Largest |v[i]|; infinite if any entry is not finite. Two entries at a time: a maximum is exact
// in any order, and a NaN is remembered (a later finite value must not hide it).
double max_norm(const double *v, int n) {
    typedef double Pair __attribute__((vector_size(16)));
    typedef long long Mask __attribute__((vector_size(16)));
    const Mask magnitude = {0x7fffffffffffffffLL, 0x7fffffffffffffffLL};
    Pair r = {0, 0};
    Mask nan = {0, 0};
    int i = 0;
    for (; i + 2 <= n; i += 2) {
        Pair x;
        std::memcpy(&x, v + i, sizeof x);
        const Pair a = reinterpret_cast<Pair>(reinterpret_cast<Mask>(x) & magnitude);
        nan |= a != a;
        r = a > r ? a : r;
    }
    double largest = r[1] > r[0] ? r[1] : r[0];
    bool any_nan = nan[0] | nan[1];
    if (i < n) {
        const double a = std::fabs(v[i]);
        any_nan = any_nan || std::isnan(a);
        if (a > largest) largest = a;
    }
    return !any_nan && std::isfinite(largest) ? largest : INFINITY;
}

int residual(N_Vector u, N_Vector f, void *user) {
    Impl &im = *static_cast<Impl *>(user);
    const State &s = im.state;
    double *fd = N_VGetArrayPointer(f);
    assemble_residual(s.mechanism, N_VGetArrayPointer(u), s.drive.data(), fd);
    im.last_residual = max_norm(fd, s.mechanism.equations);
    return std::isfinite(im.last_residual) ? 0 : 1;  // 1: recoverable, KINSOL may step shorter
}

// KINSOL asks for the Jacobian at u: values in the mechanism's pattern, kept in the state.
int jacobian(N_Vector u, N_Vector, SUNMatrix J, void *user, N_Vector, N_Vector) {
    Impl &im = *static_cast<Impl *>(user);
    State &s = im.state;
    const Mechanism &m = s.mechanism;
    const double *ud = N_VGetArrayPointer(u);
    // The first iteration's Jacobian is the one evaluated with the residual at the guess (q).
    const bool at_guess = im.values_at_guess && std::equal(ud, ud + m.coordinates, s.q.begin());
    if (!at_guess) assemble_jacobian(m, ud, s.drive.data(), s.values.data());
    im.values_at_guess = false;
    s.factor_current = false;
    s.values_current = false;  // at an iterate, not (yet) at the solution
    if (im.dense)
        for (int t = 0; t < m.values(); ++t)
            SM_ELEMENT_D(J, m.pattern_row[t], m.pattern_col[t]) = s.values[t];
    return 0;
}

// The custom linear solver (core/kinsol_custom): our structured factorisation of the values in
// state.values, which the custom SUNMatrix (content: the Impl) stands for.
int solver_setup(SUNLinearSolver S, SUNMatrix) {
    State &s = static_cast<Impl *>(S->content)->state;
    if (!s.linear->factor(s.values.data())) return SUNLS_LUFACT_FAIL;
    s.factor_current = false;  // at the Newton iterate, not (yet) at the solution
    return SUNLS_SUCCESS;
}
int solver_solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, realtype) {
    State &s = static_cast<Impl *>(S->content)->state;
    const int n = s.mechanism.equations;
    double *xd = N_VGetArrayPointer(x);
    std::copy(N_VGetArrayPointer(b), N_VGetArrayPointer(b) + n, xd);
    s.linear->solve(xd);
    return SUNLS_SUCCESS;
}
}  // namespace

PositionSolver::PositionSolver(State &state, const SolverOptions &options)
    : impl_(new Impl(state)) {
    Impl &im = *impl_;
    const Mechanism &m = state.mechanism;
    const sunindextype n = m.equations;
    im.dense = options.kinsol_dense;
    char *msg = state.message;
    const size_t size = sizeof state.message;
    im.context = sundials::make_context();
    if (!im.context) {
        set_message(msg, size, MBS_ERR_MEMORY, "SUNContext_Create failed");
        return;
    }
    SUNContext context = im.context.get();
    im.u.reset(N_VNew_Serial(n, context));
    im.scale.reset(N_VNew_Serial(n, context));
    im.work.reset(N_VNew_Serial(n, context));
    if (!im.u || !im.scale || !im.work) {
        set_message(msg, size, MBS_ERR_MEMORY, "N_VNew_Serial(%ld) failed", (long)n);
        return;
    }
    N_VConst(1.0, im.scale.get());
    if (im.dense) {
        im.matrix.reset(SUNDenseMatrix(n, n, context));
        if (im.matrix) im.linear.reset(SUNLinSol_Dense(im.u.get(), im.matrix.get(), context));
    } else {
        SUNMatrix matrix = nullptr;
        SUNLinearSolver linear = nullptr;
        mbs::make_custom_linear_solver(context, &im, solver_setup, solver_solve, matrix, linear);
        im.matrix.reset(matrix);
        im.linear.reset(linear);
    }
    if (!im.matrix || !im.linear) {
        set_message(msg, size, MBS_ERR_MEMORY, "could not create the KINSOL linear solver");
        return;
    }
    im.kinsol.reset(KINCreate(context));
    if (!im.kinsol) {
        set_message(msg, size, MBS_ERR_MEMORY, "KINCreate failed");
        return;
    }
    void *kinsol = im.kinsol.get();
    int flag;
    if ((flag = KINSetErrHandlerFn(kinsol, keep_kinsol_message, im.kinsol_message)) !=
            KIN_SUCCESS ||
        (flag = KINInit(kinsol, residual, im.u.get())) != KIN_SUCCESS ||
        (flag = KINSetUserData(kinsol, &im)) != KIN_SUCCESS ||
        (flag = KINSetLinearSolver(kinsol, im.linear.get(), im.matrix.get())) != KINLS_SUCCESS ||
        (flag = KINSetJacFn(kinsol, jacobian)) != KINLS_SUCCESS ||
        (flag = KINSetScaledStepTol(kinsol, 1e-300)) != KIN_SUCCESS) {
        set_message(msg, size, MBS_ERR_MEMORY, "KINSOL setup failed with flag %d: %s", flag,
                    im.kinsol_message);
        return;
    }
    ok_ = true;
}

PositionSolver::~PositionSolver() { delete impl_; }

mbs_status PositionSolver::solve(const SolverOptions &o) {
    Impl &im = *impl_;
    State &s = im.state;
    char *msg = s.message;
    const size_t size = sizeof s.message;
    const int n = s.mechanism.equations;
    int flag;
    void *kinsol = im.kinsol.get();
    if ((flag = KINSetFuncNormTol(kinsol, o.tolerance)) != KIN_SUCCESS ||
        (flag = KINSetNumMaxIters(kinsol, o.max_iterations)) != KIN_SUCCESS ||
        (flag = KINSetMaxSetupCalls(kinsol, o.modified_newton ? 10 : 1)) != KIN_SUCCESS)
        return set_message(msg, size, MBS_ERR_PARAMETER,
                           "KINSOL rejected the options (flag %d): tolerance = %g, "
                           "max_iterations = %d: %s",
                           flag, o.tolerance, o.max_iterations, im.kinsol_message);
    double *u = N_VGetArrayPointer(im.u.get());
    std::copy(s.q.begin(), s.q.end(), u);
    // KINSOL's own first test (initial guess accepted if ||F|| <= 0.01 tolerance), done here so
    // a step that needs no iteration does not pay for KINSOL's set-up.
    // The Jacobian comes along (it shares most of the work): if the guess is accepted it is the
    // one velocities, accelerations and multipliers need.
    assemble_residual_and_jacobian(s.mechanism, u, s.drive.data(),
                                   N_VGetArrayPointer(im.work.get()), s.values.data());
    im.last_residual = max_norm(N_VGetArrayPointer(im.work.get()), n);
    s.values_current = true;
    long iterations = 0;
    if (!(im.last_residual <= 0.01 * o.tolerance)) {
        im.kinsol_message[0] = '\0';
        s.values_current = false;
        im.values_at_guess = true;
        flag = KINSol(kinsol, im.u.get(), KIN_NONE, im.scale.get(), im.scale.get());
        const int stats_flag = KINGetNumNonlinSolvIters(kinsol, &iterations);
        if (stats_flag != KIN_SUCCESS)
            return set_message(msg, size, MBS_ERR_NOT_CONVERGED,
                               "KINGetNumNonlinSolvIters failed with flag %d", stats_flag);
        // With no line search every evaluated iterate is accepted: the last residual is the
        // final one's. A failure may have stopped elsewhere, so recompute then.
        if (flag < 0) residual(im.u.get(), im.work.get(), &im);
    } else {
        flag = KIN_INITIAL_GUESS_OK;
    }
    s.stats.iterations = static_cast<int>(iterations);
    s.stats.residual = im.last_residual;
    bool finite = std::isfinite(im.last_residual);
    if (iterations == 0 && !finite)
        return set_message(msg, size, MBS_ERR_NOT_CONVERGED,
                           "the residual at the initial guess is not finite");
    // No iteration is no licence: KINSOL may also stop before its first one with an error (its
    // set-up failing), leaving the guess and its residual above the tolerance. The guess stands
    // only on the same terms as an iterate.
    finite = finite && std::isfinite(max_norm(u, n));
    if (flag < 0 || !finite || !(im.last_residual <= o.tolerance)) {
        if (flag == KIN_LSETUP_FAIL || flag == KIN_LINSOLV_NO_RECOVERY)
            return set_message(msg, size, MBS_ERR_SINGULAR,
                               "the constraint Jacobian is singular during the position solve "
                               "(KINSOL flag %d after %ld iterations)",
                               flag, iterations);
        if (im.last_residual <= o.tolerance)  // small enough, but KINSOL reported a failure
            return set_message(msg, size, MBS_ERR_NOT_CONVERGED,
                               "position solve failed: KINSOL flag %d after %ld iterations "
                               "(residual %g, tolerance %g)%s%s",
                               flag, iterations, s.stats.residual, o.tolerance,
                               im.kinsol_message[0] ? ": " : "", im.kinsol_message);
        return set_message(msg, size, MBS_ERR_NOT_CONVERGED,
                           "position problem not converged: residual %g > tolerance %g after "
                           "%ld iterations (KINSOL flag %d%s%s)",
                           s.stats.residual, o.tolerance, iterations, flag,
                           im.kinsol_message[0] ? ": " : "", im.kinsol_message);
    }
    if (iterations > 0) std::copy(u, u + n, s.q.begin());  // else q is the accepted guess
    return MBS_OK;
}

}  // namespace mbs
