// Valid ranges of table entries (parameters, options): the test, and a sentence saying why a value
// is refused, with the value printed with every digit it needs.
#pragma once

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace stewart {

// Whether value lies in the range; NaN never does, and ends at +-DBL_MAX keep out the infinities.
inline bool in_range(double value, double min, bool min_closed, double max, bool max_closed) {
    const bool above = min_closed ? value >= min : value > min;
    const bool below = max_closed ? value <= max : value < max;
    return above && below;
}

// The shortest %g form that reads back as the same double (at most 17 digits): 1e-16 stays
// "1e-16", and 3 + 1 ulp shows as 3.0000000000000004.
struct ExactText {
    char text[32];
    explicit ExactText(double value) {
        for (int digits = 6; digits <= 17; ++digits) {
            std::snprintf(text, sizeof text, "%.*g", digits, value);
            if (!std::isfinite(value) || std::strtod(text, nullptr) == value) return;
        }
    }
    const char *c_str() const { return text; }
};

// "> 0", ">= 1", "in [0, 2]", "finite": what a value of that range must be.
inline void describe_range(double min, bool min_closed, double max, bool max_closed, char *out,
                           size_t size) {
    const bool no_min = min == -DBL_MAX && min_closed, no_max = max == DBL_MAX && max_closed;
    if (no_min && no_max) std::snprintf(out, size, "finite");
    else if (no_max)
        std::snprintf(out, size, "%s %s", min_closed ? ">=" : ">", ExactText(min).c_str());
    else if (no_min)
        std::snprintf(out, size, "%s %s", max_closed ? "<=" : "<", ExactText(max).c_str());
    else
        std::snprintf(out, size, "in %c%s, %s%c", min_closed ? '[' : '(', ExactText(min).c_str(),
                      ExactText(max).c_str(), max_closed ? ']' : ')');
}

}  // namespace stewart
