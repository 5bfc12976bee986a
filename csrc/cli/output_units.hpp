// The units of a tool's output table (--units mm,deg): SI inside, the user's at the edge.
#pragma once

#include <string>

namespace stewart {

// What an SI length and angle of the output are multiplied by, and the units' names.
struct OutputUnits {
    double length = 1.0, angle = 1.0;
    std::string length_name = "m", angle_name = "rad";
};

// "mm,deg", either order, either alone (the other stays SI): lengths m, mm, um; angles rad, deg,
// mrad, urad (the sweeps' --units). False with "TOOL: --units ..." on stderr naming the word.
bool parse_output_units(const char *tool, const char *text, OutputUnits &units);

}  // namespace stewart
