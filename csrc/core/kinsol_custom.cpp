#include "core/kinsol_custom.hpp"

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

}  // namespace

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
    std::snprintf(static_cast<char *>(user), MBS_MESSAGE_SIZE, "%s %s (%d): %s", module,
                  function, code, text);
}

}  // namespace mbs
