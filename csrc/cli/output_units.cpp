#include "cli/output_units.hpp"

#include <cstdio>
#include <cstring>
#include <vector>

#include "cli/pose_table.hpp"
#include "stewart/stewart_platform_file.h"

namespace stewart {

namespace {

// name as the length or angle unit of units; false if it names neither.
bool set_unit(const std::string &name, OutputUnits &units) {
    double per_si = 0;
    const char *si = stewart_unit_per_si(name.c_str(), &per_si);
    if (!si) return false;
    const bool angle = !std::strcmp(si, "rad");
    (angle ? units.angle : units.length) = per_si;
    (angle ? units.angle_name : units.length_name) = name;
    return true;
}

}  // namespace

bool parse_output_units(const char *tool, const char *text, OutputUnits &units) {
    OutputUnits parsed = units;
    for (const std::string &word : csv_cells(text))
        if (!set_unit(word, parsed)) {
            std::fprintf(stderr,
                         "%s: --units %s: '%s' is neither a length unit (m, cm, mm, um, "
                         "nm, in) nor an angle unit (rad, deg, mrad, urad)\n",
                         tool, text, word.c_str());
            return false;
        }
    units = parsed;
    return true;
}

bool file_output_units(const char *tool, const char *path, OutputUnits &units) {
    stewart_file_units file;
    char message[STEWART_MESSAGE_SIZE];
    if (stewart_platform_file_units(path, &file, message, sizeof message) != STEWART_OK) {
        std::fprintf(stderr, "%s: %s: %s\n", tool, path, message);
        return false;
    }
    for (const char *name : {file.length, file.angle})
        if (*name) set_unit(name, units);
    return true;
}

}  // namespace stewart
