// The parts of a KINSOL set-up with a custom direct linear solver that every user writes alike: an
// empty SUNMatrix tag (the Jacobian values live with the caller) and a SUNLinearSolver whose
// setup (factor) and solve callbacks are the caller's, and an error handler that keeps KINSOL's
// message; and serial vectors whose operations are written for their fixed length.
#pragma once

#include <kinsol/kinsol.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

namespace mbs {

using LinearSetup = int (*)(SUNLinearSolver, SUNMatrix);
using LinearSolve = int (*)(SUNLinearSolver, SUNMatrix, N_Vector, N_Vector, realtype);

// Creates matrix and solver (both with `content`, solver->content is what setup and solve get);
// false if out of memory (whatever was created is in matrix/solver, for the caller to free).
bool make_custom_linear_solver(SUNContext context, void *content, LinearSetup setup,
                               LinearSolve solve, SUNMatrix &matrix, SUNLinearSolver &solver);

// KINSOL error handler: "module function (code): text" into the char buffer at `user`, which must
// hold MBS_MESSAGE_SIZE characters.
void keep_kinsol_message(int code, const char *module, const char *function, char *text,
                         void *user);

// Replaces the operations KINSOL's Newton iteration calls on the serial vector v (length 6 only)
// by loops of that length known at compile time: on six entries the generic loops and their
// special cases cost more than the arithmetic. Clones of v inherit them. The results are those
// of the serial operations (the same sums in the same order). False (v unchanged) for another
// length.
bool use_fixed_length_ops(N_Vector v);

}  // namespace mbs
