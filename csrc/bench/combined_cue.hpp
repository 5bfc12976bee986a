// The combined cue (scenes/combined.json's formula) for the benchmark programs: every pose
// component a sinusoid, with exact first and second derivatives.
#pragma once

#include <cmath>

#include "stewart/stewart.h"

inline stewart_pose combined_cue(double t) {
    static const double mean[6] = {0, 0, 0.5, 0, 0, 0};
    static const double amp[6] = {0.05, 0.04, 0.03, 0.10, 0.08, 0.15};
    static const double w[6] = {3.0, 2.0, 4.0, 2.5, 3.5, 1.5};
    static const double phase[6] = {0.1, 0.7, 0.3, 1.1, 0.4, 0.9};
    stewart_pose p{};
    for (int i = 0; i < 6; ++i) {
        p.q[i] = mean[i] + amp[i] * std::sin(w[i] * t + phase[i]);
        p.q_dot[i] = amp[i] * w[i] * std::cos(w[i] * t + phase[i]);
        p.q_ddot[i] = -amp[i] * w[i] * w[i] * std::sin(w[i] * t + phase[i]);
    }
    return p;
}
