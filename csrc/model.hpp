// The immutable model and the mutable data block behind the opaque C handles.
#pragma once

#include <memory>

#include "kinematics/closed_form.hpp"
#include "forward/forward_state.hpp"
#include "inverse/full_model.hpp"
#include "stewart/stewart.h"

struct stewart_model {
    stewart_params params;
    stewart::PlatformGeometry geometry;
    stewart::LumpedBody platform;  // platform plus payload
    Eigen::Vector3d gravity;
    std::unique_ptr<mbs_model> full;  // the 14-body mechanism (actuator-length drivers)
    stewart::FullLayout full_layout;
};

struct stewart_data {
    const stewart_model *model;
    char message[STEWART_MESSAGE_SIZE];
    std::unique_ptr<mbs_data> full;  // state and workspaces of the full level
    stewart::ForwardState forward;   // forward kinematics: its solver and tracking history
};
