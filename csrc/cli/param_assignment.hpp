// --param NAME=VALUE, shared by the command-line tools.
#pragma once

#include <string>

#include "stewart/stewart.h"

namespace stewart {

// Splits NAME=VALUE (VALUE a whole number: sign, digits, '.', exponent, read the same in every
// locale); false with a message on stderr, prefixed by the program's name.
bool parse_assignment(const char *program, const char *assignment, std::string &name,
                      double &value);

// A platform parameter by its name (stewart_params_set); false with a message on stderr.
bool set_platform_param(const char *program, const std::string &name, double value,
                        stewart_params &params);

// --platform FILE.json: every parameter the platform file gives (stewart_platform_file.h), or
// none; false with a message on stderr naming the file, its line and the field.
bool read_platform_file(const char *program, const char *path, stewart_params &params);

}  // namespace stewart
