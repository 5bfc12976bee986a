// What the core publishes to the platform library besides its C API (mbs/mbs.h): the
// status-plus-message helper, the RAII holders of SUNDIALS objects and the set-up of KINSOL with a
// custom linear solver, which the platform's own solvers (forward kinematics' Newton, the plant's
// integrators) use as the core's do. The platform includes of the core only mbs/mbs.h and this
// header (the layer gate, tests/gates/layers.py, checks it); every other header here is the core's.
#pragma once

#include "core/kinsol_custom.hpp"
#include "core/message.hpp"
#include "core/sundials_holder.hpp"
#include "mbs/mbs.h"
