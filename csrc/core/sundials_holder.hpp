// One RAII holder for SUNDIALS objects: std::unique_ptr with the matching free function, so an
// owner frees what it made, in reverse order of declaration, on every path (a constructor that
// stops half-way included). Header-only and independent of the rest of the core: any layer that
// creates SUNDIALS objects may use it (integrators: sundials::Memory<CVodeFree>).
#pragma once

#include <memory>
#include <type_traits>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

namespace mbs::sundials {

struct ContextFree {
    void operator()(SUNContext c) const { SUNContext_Free(&c); }
};
struct VectorFree {
    void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixFree {
    void operator()(SUNMatrix m) const { SUNMatDestroy(m); }
};
struct LinearSolverFree {
    void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};
// A solver's memory block (KINSOL, CVODE, ARKODE...), freed by its void ** free function.
template <void (*Free)(void **)>
struct MemoryFree {
    void operator()(void *memory) const { Free(&memory); }
};

using Context = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextFree>;
using Vector = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorFree>;
using Matrix = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixFree>;
using LinearSolver = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverFree>;
template <void (*Free)(void **)>
using Memory = std::unique_ptr<void, MemoryFree<Free>>;

// A new context (null if SUNDIALS could not make one).
inline Context make_context() {
    SUNContext c = nullptr;
    return Context(SUNContext_Create(nullptr, &c) == 0 ? c : nullptr);
}

}  // namespace mbs::sundials
