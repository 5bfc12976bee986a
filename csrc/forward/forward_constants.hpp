// What forward kinematics keeps in the model (stewart_model::forward, made when the model is
// made): the one header of the direction the model includes.
#pragma once

#include "forward/branch.hpp"
#include "forward/continuation.hpp"

namespace stewart {

// Of the model, worked out when it is made: the sign of the leg Jacobian's determinant at home
// (0: singular there, no working assembly mode), the bounds on pairs of lengths, and the
// shortest leg's stroke range (a tracked platform point moving farther is a jump).
struct ForwardConstants {
    int working_sign = 0;
    LengthPairBounds pair_bounds = {};
    double shortest_stroke_range = 0;
    BranchSides sides;  // the working mode's side of every Cardan
    // Home's Cardan-to-Cardan lengths and the proven step there (tolerance 0); the largest
    // |b_k| / r_t.
    double home_lengths[6] = {0};
    ProvenStep home_step;
    double arm = 0;
};

// The constants of geometry with the parameters p (home height, strokes); STEWART_ERR_SINGULAR
// (message) if the leg Jacobian is singular at home.
stewart_status forward_constants(const PlatformGeometry &geometry, const stewart_params &p,
                                 ForwardConstants &out, char *msg, size_t size);

}  // namespace stewart
