// The struct behind the stewart_forward handle (stewart_forward.h): the model, the options and the
// tracking state; seen by forward kinematics' API files and the batch.
#pragma once

#include "forward/forward_state.hpp"
#include "model.hpp"
#include "stewart/stewart_forward.h"

struct stewart_forward {
    const stewart_model *model;
    stewart_forward_options options;
    mutable char message[STEWART_MESSAGE_SIZE];  // a refused save (const) says why too
    stewart::ForwardState state;                 // its Newton solver and tracking history
};
