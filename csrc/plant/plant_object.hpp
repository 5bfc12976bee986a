// The plant object's fields, shared by the files of its C API (plant_api.cpp: life cycle and
// step; plant_derivatives_api.cpp: the state's time derivatives). Not part of the public API.
#pragma once

#include "limits/limit_check.hpp"
#include "model.hpp"
#include "plant/plant_integrator.hpp"
#include "stewart/stewart_plant.h"

namespace stewart {
namespace plant {
constexpr double kMinCosPitch = 1e-9;  // roll and yaw rates are undefined at pitch = +-90 deg
}  // namespace plant
}  // namespace stewart

struct stewart_plant {
    const stewart_model *model = nullptr;
    stewart_plant_options options{};
    stewart::plant::DynamicsModel dynamics;
    stewart::plant::Integrator integrator;
    double time = 0;
    // the platform, then the windings' currents (plant::state_count)
    double y[stewart::plant::kMaxStates] = {0};
    double angles[3] = {0};  // roll, pitch, yaw of the state, continuous from step to step
    double force[STEWART_LEGS] = {0};  // at the current time (the end of the last step)
    int warnings = 0;
    stewart::LimitConstants limits;  // joint angles and interference, warned as strokes are
    // where the steps' last exact limit check found nothing, and how far from failing: a pose
    // near it needs no check (not part of the state: any pose's clearance is true of it)
    stewart::LimitClearance limit_clearance;
    // What the last step found at y that the next one needs at its start (valid false after
    // anything else set y): p + R b_k - a_k of every leg, as the step's zero-length test forms
    // them, and y's principal roll, pitch, yaw (plant::principal_angles, the integrator's start)
    double leg_vectors[STEWART_LEGS][3] = {};
    double principal_angles[3] = {0, 0, 0};
    bool step_end_valid = false;
    double step_hint = 0;  // first internal step of the next communication step (0: estimate)
    stewart_plant_statistics stats{};
    mutable char message[STEWART_MESSAGE_SIZE] = "";  // a refused save (const) says why too
};

// The legs' forces and drive outputs of o (force, current, voltage, motor speed and torque,
// electrical power, the drive-limit bits) at the evaluation e of the inputs (plant_api.cpp).
void plant_drive_outputs(const stewart_plant &p, const double *input,
                         const stewart::plant::Evaluation &e, stewart_plant_output &o);
