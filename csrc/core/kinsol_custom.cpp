#include "core/kinsol_custom.hpp"

#include <cmath>
#include <cstdio>

#include "mbs/mbs.h"

namespace mbs {

namespace {

SUNMatrix_ID matrix_id(SUNMatrix) { return SUNMATRIX_CUSTOM; }
int matrix_zero(SUNMatrix) { return 0; }  // every value is overwritten by the Jacobian
void matrix_destroy(SUNMatrix A) { SUNMatFreeEmpty(A); }

SUNLinearSolver_Type solver_type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
SUNLinearSolver_ID solver_id(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }
int solver_initialize(SUNLinearSolver) { return SUNLS_SUCCESS; }
sunindextype solver_last_flag(SUNLinearSolver) { return 0; }
int solver_free(SUNLinearSolver S) {
    S->content = nullptr;
    SUNLinSolFreeEmpty(S);
    return 0;
}

// The serial operations with the length a constant.
template <int N>
struct FixedOps {
    static double *data(N_Vector v) { return NV_DATA_S(v); }
    static void linear_sum(realtype a, N_Vector x, realtype b, N_Vector y, N_Vector z) {
        const double *xd = data(x), *yd = data(y);
        double *zd = data(z);
#pragma GCC unroll 6
        for (int i = 0; i < N; ++i) zd[i] = a * xd[i] + b * yd[i];
    }
    static void constant(realtype c, N_Vector z) {
        double *zd = data(z);
#pragma GCC unroll 6
        for (int i = 0; i < N; ++i) zd[i] = c;
    }
    static void prod(N_Vector x, N_Vector y, N_Vector z) {
        const double *xd = data(x), *yd = data(y);
        double *zd = data(z);
#pragma GCC unroll 6
        for (int i = 0; i < N; ++i) zd[i] = xd[i] * yd[i];
    }
    static void div(N_Vector x, N_Vector y, N_Vector z) {
        const double *xd = data(x), *yd = data(y);
        double *zd = data(z);
#pragma GCC unroll 6
        for (int i = 0; i < N; ++i) zd[i] = xd[i] / yd[i];
    }
    static void scale(realtype c, N_Vector x, N_Vector z) {
        const double *xd = data(x);
        double *zd = data(z);
#pragma GCC unroll 6
        for (int i = 0; i < N; ++i) zd[i] = c * xd[i];
    }
    static void abs(N_Vector x, N_Vector z) {
        const double *xd = data(x);
        double *zd = data(z);
#pragma GCC unroll 6
        for (int i = 0; i < N; ++i) zd[i] = std::fabs(xd[i]);
    }
    static void inv(N_Vector x, N_Vector z) {
        const double *xd = data(x);
        double *zd = data(z);
#pragma GCC unroll 6
        for (int i = 0; i < N; ++i) zd[i] = 1.0 / xd[i];
    }
    static realtype dot(N_Vector x, N_Vector y) {
        const double *xd = data(x), *yd = data(y);
        double sum = 0;
#pragma GCC unroll 6
        for (int i = 0; i < N; ++i) sum += xd[i] * yd[i];
        return sum;
    }
    static realtype max_norm(N_Vector x) {
        const double *xd = data(x);
        double largest = 0;
#pragma GCC unroll 6
        for (int i = 0; i < N; ++i)
            if (std::fabs(xd[i]) > largest) largest = std::fabs(xd[i]);
        return largest;
    }
    static realtype weighted_l2_norm(N_Vector x, N_Vector w) {
        const double *xd = data(x), *wd = data(w);
        double sum = 0;
#pragma GCC unroll 6
        for (int i = 0; i < N; ++i) sum += (xd[i] * wd[i]) * (xd[i] * wd[i]);
        return std::sqrt(sum);
    }
    static realtype min(N_Vector x) {
        const double *xd = data(x);
        double smallest = xd[0];
#pragma GCC unroll 6
        for (int i = 1; i < N; ++i)
            if (xd[i] < smallest) smallest = xd[i];
        return smallest;
    }
    static realtype l1_norm(N_Vector x) {
        const double *xd = data(x);
        double sum = 0;
#pragma GCC unroll 6
        for (int i = 0; i < N; ++i) sum += std::fabs(xd[i]);
        return sum;
    }
    static void install(N_Vector v) {
        N_Vector_Ops o = v->ops;
        o->nvlinearsum = linear_sum;
        o->nvconst = constant;
        o->nvprod = prod;
        o->nvdiv = div;
        o->nvscale = scale;
        o->nvabs = abs;
        o->nvinv = inv;
        o->nvdotprod = dot;
        o->nvmaxnorm = max_norm;
        o->nvwl2norm = weighted_l2_norm;
        o->nvmin = min;
        o->nvl1norm = l1_norm;
    }
};

}  // namespace

bool use_fixed_length_ops(N_Vector v) {
    if (!v || N_VGetVectorID(v) != SUNDIALS_NVEC_SERIAL || NV_LENGTH_S(v) != 6) return false;
    FixedOps<6>::install(v);
    return true;
}

bool make_custom_linear_solver(SUNContext context, void *content, LinearSetup setup,
                               LinearSolve solve, SUNMatrix &matrix, SUNLinearSolver &solver) {
    matrix = SUNMatNewEmpty(context);
    solver = SUNLinSolNewEmpty(context);
    if (!matrix || !solver) return false;
    matrix->content = content;
    matrix->ops->getid = matrix_id;
    matrix->ops->zero = matrix_zero;
    matrix->ops->destroy = matrix_destroy;
    solver->content = content;
    solver->ops->gettype = solver_type;
    solver->ops->getid = solver_id;
    solver->ops->initialize = solver_initialize;
    solver->ops->setup = setup;
    solver->ops->solve = solve;
    solver->ops->lastflag = solver_last_flag;
    solver->ops->free = solver_free;
    return true;
}

void keep_kinsol_message(int code, const char *module, const char *function, char *text,
                         void *user) {
    std::snprintf(static_cast<char *>(user), MBS_MESSAGE_SIZE, "%s %s (%d): %s", module, function,
                  code, text);
}

}  // namespace mbs
