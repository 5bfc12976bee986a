// Numbers read from text the same in every locale: strtod and sscanf follow the process's
// LC_NUMERIC, so under a decimal comma (de_DE, fr_FR) "12.5" reads as 12. std::from_chars does not.
#pragma once

#include <charconv>
#include <cmath>
#include <limits>
#include <string_view>
#include <system_error>

namespace stewart {

// Decimal digits before the point of a number's value (its order of magnitude, about): positive
// for one that overflows a double, negative for one that underflows. text: from_chars' syntax.
inline long decimal_magnitude(std::string_view text) {
    size_t i = text.find_first_not_of("+-");
    if (i == std::string_view::npos) return 0;
    long digits = 0, leading_zeros = 0;
    bool before_point = true, nonzero = false;
    for (; i < text.size() && text[i] != 'e' && text[i] != 'E'; ++i) {
        if (text[i] == '.') {
            before_point = false;
            continue;
        }
        if (text[i] != '0') nonzero = true;
        if (before_point && nonzero) ++digits;
        if (!before_point && !nonzero) ++leading_zeros;
    }
    long exponent = 0;
    if (i < text.size()) {
        const std::string_view e = text.substr(i + 1);
        const bool minus = !e.empty() && e[0] == '-';
        for (char c : e.substr(!e.empty() && (e[0] == '-' || e[0] == '+')))
            if (exponent < 100000) exponent = 10 * exponent + (c - '0');
        if (minus) exponent = -exponent;
    }
    return (digits > 0 ? digits : -leading_zeros) + exponent;
}

// The whole of text as a double: an optional sign, digits with an optional '.', an optional
// exponent ("inf" and "nan" too; the caller refuses what is not finite). False if anything else
// is in text. A value beyond the doubles reads as +-inf, one below the smallest as +-0, as strtod.
inline bool read_double(std::string_view text, double &value) {
    if (!text.empty() && text[0] == '+') {
        text.remove_prefix(1);
        if (!text.empty() && (text[0] == '-' || text[0] == '+')) return false;
    }
    const char *end = text.data() + text.size();
    const std::from_chars_result r = std::from_chars(text.data(), end, value);
    if (r.ptr != end || text.empty()) return false;
    if (r.ec == std::errc::result_out_of_range) {
        const bool negative = text[0] == '-';
        value = decimal_magnitude(text) > 0 ? std::numeric_limits<double>::infinity() : 0.0;
        if (negative) value = -value;
        return true;
    }
    return r.ec == std::errc();
}

}  // namespace stewart
