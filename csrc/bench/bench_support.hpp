// What every benchmark program needs: the clock, percentiles of its samples, and the thesis
// platform's model (the default parameters) with its error said under the program's name.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <utility>
#include <vector>

#include "stewart/stewart.h"

namespace bench {

using Clock = std::chrono::steady_clock;

// Nanoseconds from start to now.
inline double ns_since(Clock::time_point start) {
    return std::chrono::duration<double, std::nano>(Clock::now() - start).count();
}

// The sample at fraction p (0 to 1) of the sorted samples, nearest rank; 0 for none.
inline double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0;
    const size_t i = std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5));
    std::nth_element(v.begin(), v.begin() + i, v.end());
    return v[i];
}

// The middle sample (the upper one of an even count).
inline double median(std::vector<double> v) { return percentile(std::move(v), 0.5); }

// The model of `params` (the thesis platform's defaults if null); null after printing
// "program: message" to stderr.
inline stewart_model *make_model(const char *program, const stewart_params *params = nullptr) {
    stewart_params defaults;
    if (!params) stewart_params_default(&defaults), params = &defaults;
    char msg[STEWART_MESSAGE_SIZE];
    stewart_model *model = stewart_model_create(params, msg, sizeof msg);
    if (!model) std::fprintf(stderr, "%s: %s\n", program, msg);
    return model;
}

}  // namespace bench
