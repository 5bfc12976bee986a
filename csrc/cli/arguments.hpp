// The command line every tool parses the same way: options with a value, flags, two paths.
#pragma once

#include <cstdio>
#include <functional>
#include <vector>

namespace stewart {

// One option of a tool's command line.
struct CliOption {
    const char *flag;        // e.g. "--fidelity"
    const char *value_hint;  // its value, for "needs a value (...)"; nullptr: a flag, no value
    std::function<int(const char *value)> take;  // 0: taken; else the exit code (it said why)
    bool inline_value = false;  // a flag that may also be given as FLAG=VALUE (take gets VALUE)
};

// Parses argv[1..]: --help or -h prints usage to stdout; an option takes its value (a missing one
// is "TOOL: FLAG needs a value (HINT)" and usage on stderr; a flag with inline_value takes
// FLAG=VALUE too); an unknown "-x" is "TOOL: unknown
// option '-x'" and usage on stderr; every other argument is a path, exactly n_paths of them (else
// usage on stderr). Returns -1 when the tool goes on, else its exit code.
int parse_command_line(const char *tool, int argc, char **argv,
                       const std::vector<CliOption> &options, const char *paths[], int n_paths,
                       int (*usage)(FILE *));

}  // namespace stewart
