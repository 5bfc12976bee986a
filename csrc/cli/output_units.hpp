// The units of a tool's output (--units mm,deg): SI inside, the user's at the edge.
#pragma once

#include <string>

namespace stewart {

// What an SI length and angle of the output are multiplied by, and the units' names.
struct OutputUnits {
    double length = 1.0, angle = 1.0;
    std::string length_name = "m", angle_name = "rad";
};

// "mm,deg", either order, either alone (the other stays as units has it): the units a platform
// file may name (stewart_unit_per_si: m, cm, mm, um, nm, in; rad, mrad, urad, deg), the same
// factors. False with "TOOL: --units ..." on stderr naming the word, units unchanged.
bool parse_output_units(const char *tool, const char *text, OutputUnits &units);

// The units of the platform file at path (stewart_platform_file_units), the ones it does not
// state as units has them; false with "TOOL: PATH: ..." on stderr.
bool file_output_units(const char *tool, const char *path, OutputUnits &units);

}  // namespace stewart
