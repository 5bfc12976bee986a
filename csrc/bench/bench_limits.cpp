// Limit check and axis ranges speed (the goals: <= 2 us and <= 100 us per pose, so that a
// controller can check every pose it commands): median,
// p99 and max microseconds per call over random poses of the thesis platform's workspace (all
// within every limit), and how often each class ends an axis range; for the thesis defaults and
// for a vendor-like set of limits (joints 0.45 rad, legs 0.2 m thick, condition 60). Per pose the
// fastest of 5 timings (see time_each). --near-singular: the hard case of the ranges' proven
// steps instead, poses 0.01 to 0.04 rad short of the thesis platform's yaw singularity (90 deg)
// with only the condition limited (warn_condition 1e3; strokes 0.05 to 3 m, no joint or
// interference limit), where the condition's proven steps shrink with the distance to the
// singularity (docs/limits.md 7.2: after 32 of them on a side, steps of 5e-3).
// usage: bench-limits [POSES (2000)] [--vendor | --near-singular] [--check-only | --ranges-only]
// [--save FILE]: the --*-only forms make exactly POSES calls of one function for one set of
// limits (studies/bench/limits.sh counts instructions inside it); --save appends the printed
// numbers to FILE.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "bench/bench_support.hpp"
#include "stewart/stewart_limits.h"

namespace {

using bench::percentile;

// Random poses around home (or near the yaw singularity), kept if within every limit.
std::vector<stewart_limits_input> workspace_poses(stewart_limits *limits, int n, bool singular) {
    std::mt19937_64 rng(19);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<stewart_limits_input> poses;
    while (static_cast<int>(poses.size()) < n) {
        stewart_limits_input in = {{0.08 * u(rng), 0.08 * u(rng), 0.5 + 0.08 * u(rng),
                                    0.15 * u(rng), 0.15 * u(rng), 0.2 * u(rng)}};
        if (singular) {
            for (int i = 0; i < 5; ++i) in.q[i] = (i == 2 ? 0.5 : 0.0) + 0.02 * u(rng);
            in.q[5] = M_PI / 2 + (u(rng) < 0 ? -1 : 1) * (0.025 + 0.015 * u(rng));
        }
        stewart_limits_output out;
        if (stewart_limits_check(limits, &in, &out) == STEWART_OK && out.failed == 0)
            poses.push_back(in);
    }
    return poses;
}

// Per pose, the fastest of `rounds` timings of `repeats` calls each, per call: the pose's own
// cost (a call preempted on this shared machine otherwise shows as milliseconds).
template <class Call>
std::vector<double> time_each(const std::vector<stewart_limits_input> &poses, int repeats,
                              int rounds, Call call) {
    std::vector<double> us;
    for (const stewart_limits_input &in : poses) {
        double best = HUGE_VAL;
        for (int round = 0; round < rounds; ++round) {
            const auto start = bench::Clock::now();
            for (int r = 0; r < repeats; ++r) call(in);
            best = std::min(best, 1e-3 * bench::ns_since(start) / repeats);
        }
        us.push_back(best);
    }
    return us;
}

// Prints a line, and appends it to `save` if not NULL.
void say(FILE *save, const char *line) {
    std::fputs(line, stdout);
    if (save) std::fputs(line, save);
}

void report(FILE *save, const char *what, const std::vector<double> &us) {
    char line[160];
    std::snprintf(line, sizeof line,
                  "%-12s median %8.3f us  p99 %8.3f us  max %8.3f us  (%zu poses)\n", what,
                  percentile(us, 0.5), percentile(us, 0.99), percentile(us, 1.0), us.size());
    say(save, line);
}

}  // namespace

int main(int argc, char **argv) {
    int n = 2000;
    bool check = true, ranges = true, vendor = false, singular = false;
    const char *save_path = nullptr;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--check-only")) ranges = false;
        else if (!std::strcmp(argv[i], "--ranges-only")) check = false;
        else if (!std::strcmp(argv[i], "--vendor")) vendor = true;
        else if (!std::strcmp(argv[i], "--near-singular")) singular = true;
        else if (!std::strcmp(argv[i], "--save") && i + 1 < argc) save_path = argv[++i];
        else n = std::max(1, std::atoi(argv[i]));
    }
    FILE *save = save_path ? std::fopen(save_path, "a") : nullptr;
    if (save_path && !save) {
        std::fprintf(stderr, "bench-limits: cannot open --save file %s\n", save_path);
        return 1;
    }
    char message[STEWART_MESSAGE_SIZE];
    stewart_params params;
    stewart_params_default(&params);
    stewart_limits_options options;
    stewart_limits_options_default(&options);
    if (vendor) {
        params.base_joint_limit = params.platform_joint_limit = 0.45;
        params.leg_diameter = 0.2;
        options.warn_condition = 60.0;
    } else if (singular) {
        for (int k = 0; k < STEWART_LEGS; ++k) {
            params.stroke_min[k] = 0.05;
            params.stroke_max[k] = 3.0;
        }
        params.base_joint_limit = params.platform_joint_limit = M_PI;
        params.leg_diameter = 0.0;
    }
    char title[80];
    std::snprintf(title, sizeof title, "%s limits\n",
                  vendor     ? "vendor-like"
                  : singular ? "near-singular (condition only)"
                             : "thesis (default)");
    say(save, title);
    stewart_model *model = stewart_model_create(&params, message, sizeof message);
    stewart_limits *limits =
        model ? stewart_limits_create(model, &options, message, sizeof message) : nullptr;
    if (!limits) {
        std::fprintf(stderr, "bench-limits: %s\n", message);
        if (save) std::fclose(save);
        stewart_model_free(model);
        return 1;
    }
    const std::vector<stewart_limits_input> poses = workspace_poses(limits, n, singular);
    stewart_limits_output out;
    stewart_axis_ranges r;
    if (check != ranges) {  // exactly n calls of one function, for callgrind
        for (const stewart_limits_input &in : poses)
            check ? (void)stewart_limits_check(limits, &in, &out)
                  : (void)stewart_limits_ranges(limits, &in, &r);
    } else {
        report(save, "check", time_each(poses, 20, 5, [&](const stewart_limits_input &in) {
                   stewart_limits_check(limits, &in, &out);
               }));
        report(save, "ranges", time_each(poses, 1, 5, [&](const stewart_limits_input &in) {
                   stewart_limits_ranges(limits, &in, &r);
               }));
        long ends[STEWART_LIMIT_AXIS + 1] = {0};  // the leg classes never end a range
        for (const stewart_limits_input &in : poses) {
            stewart_limits_ranges(limits, &in, &r);
            for (int a = 0; a < 6; ++a) {
                ++ends[r.min_limit[a]];
                ++ends[r.max_limit[a]];
            }
        }
        char line[240] = "range ends by class:";
        for (int c = 0; c <= STEWART_LIMIT_AXIS; ++c)
            std::snprintf(line + std::strlen(line), sizeof line - std::strlen(line), " %s %ld",
                          stewart_limit_class_name(c), ends[c]);
        std::strncat(line, "\n", sizeof line - std::strlen(line) - 1);
        say(save, line);
    }
    if (save) std::fclose(save);
    stewart_limits_free(limits);
    stewart_model_free(model);
    return 0;
}
