// stewart._core: the nanobind extension over the C API (stewart.h, stewart_batch.h). It holds a
// model, and per Platform.inverse, forward or simulate call one run object (the call's arrays and
// solver or plant) whose rows(a, b) runs a slice; Python (stewart/platform.py) shapes arrays and
// results and takes Ctrl-C between slices. Each direction's part is in its own file (_core.hpp).
#include "_core.hpp"

NB_MODULE(_core, m) {
    using namespace stewart_core;
    m.doc() = "The C library of the Stewart platform solver (use the stewart package instead).";
    bind_model(m);  // first: the others' signatures name Model
    bind_tables(m);
    bind_inverse(m);
    bind_forward(m);
    bind_plant(m);
    bind_linearize(m);
    bind_limits(m);
    bind_cueing(m);
}
