#include "cli/param_assignment.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace stewart {

bool parse_assignment(const char *program, const char *assignment, std::string &name,
                      double &value) {
    const char *eq = std::strchr(assignment, '=');
    if (!eq) {
        std::fprintf(stderr, "%s: --param '%s' is not NAME=VALUE\n", program, assignment);
        return false;
    }
    name.assign(assignment, eq);
    char *end = nullptr;
    value = std::strtod(eq + 1, &end);
    if (end == eq + 1 || *end != '\0') {
        std::fprintf(stderr, "%s: --param %s: '%s' is not a number\n", program, name.c_str(),
                     eq + 1);
        return false;
    }
    return true;
}

bool set_platform_param(const char *program, const std::string &name, double value,
                        stewart_params &params) {
    char message[STEWART_MESSAGE_SIZE];
    if (stewart_params_set(&params, name.c_str(), value, message, sizeof message) != STEWART_OK) {
        std::fprintf(stderr, "%s: --param: %s\n", program, message);
        return false;
    }
    return true;
}

}  // namespace stewart
