// stewart-solve --forward: actuator-length CSV in, platform pose CSV out.
#pragma once

#include <string>

#include "cli/output_units.hpp"
#include "stewart/stewart_forward.h"

namespace stewart {

// Reads IN.csv (columns t,L1..L6, optionally L_dot1..L_dot6 and L_ddot1..L_ddot6, any order,
// other columns ignored), solves every row (the first from guess if not null, each later one
// tracking from the one before; with cold, every row on its own from guess or else home) and
// writes OUT.csv (t,x,y,z,roll,pitch,yaw, the pose rates and
// accelerations when their inputs are given, iterations,residual,condition), its lengths and
// angles in `units`. Returns 0, or 1 with a message on stderr naming the file line (and the leg)
// and no OUT.csv written.
int run_forward(const char *in_path, const char *out_path, const stewart_params &params,
                const stewart_forward_options &options, const double *guess, bool cold = false,
                const OutputUnits &units = OutputUnits());

}  // namespace stewart
