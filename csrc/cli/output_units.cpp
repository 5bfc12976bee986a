#include "cli/output_units.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

#include "cli/pose_table.hpp"

namespace stewart {

bool parse_output_units(const char *tool, const char *text, OutputUnits &units) {
    struct Unit {
        const char *name;
        double factor;
        bool angle;
    };
    static const Unit kUnits[] = {{"m", 1.0, false},   {"mm", 1e3, false},
                                  {"um", 1e6, false},  {"rad", 1.0, true},
                                  {"deg", 180.0 / M_PI, true}, {"mrad", 1e3, true},
                                  {"urad", 1e6, true}};
    OutputUnits parsed;
    for (const std::string &word : csv_cells(text)) {
        const Unit *found = nullptr;
        for (const Unit &u : kUnits)
            if (word == u.name) found = &u;
        if (!found) {
            std::fprintf(stderr, "%s: --units %s: '%s' is neither a length unit (m, mm, um) nor "
                         "an angle unit (rad, deg, mrad, urad)\n", tool, text, word.c_str());
            return false;
        }
        (found->angle ? parsed.angle : parsed.length) = found->factor;
        (found->angle ? parsed.angle_name : parsed.length_name) = found->name;
    }
    units = parsed;
    return true;
}

}  // namespace stewart
