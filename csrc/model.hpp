// The immutable model behind the stewart_model handle, with what each direction keeps of it, and the
// inverse solver's struct; seen only by the API files (model.cpp, batch.cpp, each direction's
// *_api.cpp and the handle headers of the others: forward/forward_object.hpp,
// plant/plant_object.hpp).
#pragma once

#include <memory>

#include "drives/leg_drive.hpp"
#include "forward/forward_constants.hpp"
#include "inverse/full_model.hpp"
#include "kinematics/closed_form.hpp"
#include "kinematics/frames.hpp"
#include "stewart/stewart.h"

struct stewart_model {
    stewart_params given;   // as the caller gave them (stewart_model_params)
    stewart_params params;  // in the solvers' z-up frames (params_in_solver_frames)
    stewart::PlatformGeometry geometry;
    stewart::LumpedBody platform;  // platform plus payload
    Eigen::Vector3d gravity;
    std::unique_ptr<mbs_model> full;  // the 14-body mechanism (actuator-length drivers)
    stewart::FullLayout full_layout;
    stewart::ForwardConstants forward;  // what forward kinematics needs from the geometry
    stewart::Frames frames;  // tool and user frames: the poses given and returned are the tool's
    bool length_offsets;     // some length_offset is not 0: lengths given and returned differ
    stewart::LegDrive drive[STEWART_LEGS];  // each leg's drive (motor_per_leg 0: none)
    bool drives;                            // some leg has a drive
};

struct stewart_inverse {
    const stewart_model *model;
    stewart_inverse_options options;
    mutable char message[STEWART_MESSAGE_SIZE];  // a refused save (const) says why too
    std::unique_ptr<mbs_data> full;              // state and workspaces of the full level
};
