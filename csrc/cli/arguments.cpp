#include "cli/arguments.hpp"

#include <cstring>

namespace stewart {

int parse_command_line(const char *tool, int argc, char **argv,
                       const std::vector<CliOption> &options, const char *paths[], int n_paths,
                       int (*usage)(FILE *)) {
    int found = 0;
    for (int i = 1; i < argc; ++i) {
        const char *arg = argv[i];
        if (!std::strcmp(arg, "--help") || !std::strcmp(arg, "-h")) return usage(stdout);
        const CliOption *option = nullptr;
        const char *value = nullptr;
        for (const CliOption &o : options) {
            const size_t n = std::strlen(o.flag);
            if (!std::strcmp(arg, o.flag)) option = &o;
            if (o.inline_value && !std::strncmp(arg, o.flag, n) && arg[n] == '=')
                option = &o, value = arg + n + 1;
        }
        if (option) {
            if (option->value_hint && !value) {
                if (i + 1 == argc) {
                    std::fprintf(stderr, "%s: %s needs a value (%s)\n", tool, arg,
                                 option->value_hint);
                    return usage(stderr);
                }
                value = argv[++i];
            }
            if (const int code = option->take(value)) return code;
        } else if (arg[0] == '-' && arg[1] != '\0') {
            std::fprintf(stderr, "%s: unknown option '%s'\n", tool, arg);
            return usage(stderr);
        } else if (found < n_paths) {
            paths[found++] = arg;
        } else {
            return usage(stderr);
        }
    }
    return found == n_paths ? -1 : usage(stderr);
}

}  // namespace stewart
