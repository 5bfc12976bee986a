#include "cli/param_assignment.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

#include "stewart/stewart_platform_file.h"

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

bool read_platform_file(const char *program, const char *path, stewart_params &params) {
    constexpr std::streamsize kMaxBytes = 1 << 20;  // a platform file is a few kB
    std::ifstream file(path, std::ios::binary);
    if (!file) {
        std::fprintf(stderr, "%s: --platform %s: cannot open the file\n", program, path);
        return false;
    }
    std::string text;
    text.resize(kMaxBytes + 1);
    file.read(&text[0], kMaxBytes + 1);
    if (file.bad()) {
        std::fprintf(stderr, "%s: --platform %s: cannot read the file\n", program, path);
        return false;
    }
    text.resize(static_cast<size_t>(file.gcount()));
    if (static_cast<std::streamsize>(text.size()) > kMaxBytes) {
        std::fprintf(stderr, "%s: --platform %s: larger than %ld bytes, not a platform file\n",
                     program, path, static_cast<long>(kMaxBytes));
        return false;
    }
    char message[STEWART_MESSAGE_SIZE];
    if (stewart_params_read_json(&params, text.data(), text.size(), nullptr, message,
                                 sizeof message) != STEWART_OK) {
        std::fprintf(stderr, "%s: --platform %s: %s\n", program, path, message);
        return false;
    }
    return true;
}

}  // namespace stewart
