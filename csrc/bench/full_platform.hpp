// The 14-body platform as the benchmarks of the core take it: the geometry, the mechanism and
// its layout, made by the library's own builders, as stewart_model_create makes them, without
// the API's model (model.hpp is the API files' alone).
#pragma once

#include <cstdio>
#include <memory>

#include "inverse/full_model.hpp"
#include "kinematics/closed_form.hpp"

struct FullPlatform {
    stewart::PlatformGeometry geometry;
    stewart::FullLayout full_layout;
    std::unique_ptr<mbs_model> full;  // null if the build failed (the message was printed)

    explicit FullPlatform(const stewart_params &params)
        : geometry(stewart::platform_geometry(params)) {
        char msg[STEWART_MESSAGE_SIZE];
        full = stewart::build_full_platform(params, stewart::FullDrive::ActuatorLengths,
                                            full_layout, msg, sizeof msg);
        if (!full) std::fprintf(stderr, "%s\n", msg);
    }
};
