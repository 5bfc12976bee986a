// The immutable model and the mutable data block behind the opaque C handles.
#pragma once

#include "platform/closed_form.hpp"
#include "stewart/stewart.h"

struct stewart_model {
    stewart_params params;
    stewart::PlatformGeometry geometry;
    stewart::LumpedBody platform;  // platform plus payload
    Eigen::Vector3d gravity;
};

struct stewart_data {
    const stewart_model *model;
    char message[STEWART_MESSAGE_SIZE];
};
