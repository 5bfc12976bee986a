#include "cli/param_assignment.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "stewart/stewart_platform_file.h"
#include "util/number_text.hpp"

namespace stewart {

bool parse_assignment(const char *program, const char *assignment, std::string &name,
                      double &value) {
    const char *eq = std::strchr(assignment, '=');
    if (!eq) {
        std::fprintf(stderr, "%s: --param '%s' is not NAME=VALUE\n", program, assignment);
        return false;
    }
    name.assign(assignment, eq);
    if (!read_double(eq + 1, value)) {
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

bool read_platform_file(const char *program, const char *path, stewart_params &params) {
    char message[STEWART_MESSAGE_SIZE];
    if (stewart_params_read_json_file(&params, path, nullptr, message, sizeof message) !=
        STEWART_OK) {
        std::fprintf(stderr, "%s: --platform %s: %s\n", program, path, message);
        return false;
    }
    return true;
}

}  // namespace stewart
