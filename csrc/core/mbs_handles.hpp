// What the opaque mbs_model and mbs_data handles hold (shared by the C API and the builders).
#pragma once

#include "core/builder.hpp"
#include "core/state.hpp"
#include "mbs/mbs.h"

struct mbs_model {
    mbs::Mechanism mechanism;
    char message[MBS_MESSAGE_SIZE] = "";
    mbs::Builder builder() { return mbs::Builder{mechanism, message, sizeof message}; }
};

struct mbs_data {
    const mbs_model *model;
    mbs::State state;
    mbs_data(const mbs_model *m, const mbs::SolverOptions &kind)
        : model(m), state(m->mechanism, kind) {}
};
