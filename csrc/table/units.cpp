#include "table/units.hpp"

#include <cstring>

#include "stewart/stewart_table.h"
#include "util/number_text.hpp"

namespace stewart {

namespace {

// Inches are exactly 0.0254 m; degrees convert as the table's own STEWART_DEG does.
const Unit kUnits[] = {
    {"m", "m", 0, 1.0, 1.0},
    {"cm", "m", -2, 1.0, 1e2},
    {"mm", "m", -3, 1.0, 1e3},
    {"um", "m", -6, 1.0, 1e6},
    {"\xC2\xB5m", "m", -6, 1.0, 1e6},
    {"nm", "m", -9, 1.0, 1e9},
    {"in", "m", 0, 0.0254, 1.0 / 0.0254},
    {"rad", "rad", 0, 1.0, 1.0},
    {"mrad", "rad", -3, 1.0, 1e3},
    {"urad", "rad", -6, 1.0, 1e6},
    {"\xC2\xB5rad", "rad", -6, 1.0, 1e6},
    {"deg", "rad", 0, STEWART_PI / 180.0, 180.0 / STEWART_PI},
};

}  // namespace

const Unit *find_unit(std::string_view name) {
    for (const Unit &u : kUnits)
        if (name == u.name) return &u;
    return nullptr;
}

size_t json_number_length(std::string_view text) {
    size_t i = 0;
    auto digits = [&] {
        const size_t from = i;
        while (i < text.size() && text[i] >= '0' && text[i] <= '9') ++i;
        return i > from;
    };
    if (i < text.size() && text[i] == '-') ++i;
    if (i < text.size() && text[i] == '0') {
        ++i;
    } else if (!digits()) {
        return 0;
    }
    if (i < text.size() && text[i] == '.') {
        ++i;
        if (!digits()) return 0;
    }
    if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
        ++i;
        if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
        if (!digits()) return 0;
    }
    return i;
}

bool split_quantity(std::string_view text, std::string &number, std::string &unit) {
    const size_t n = json_number_length(text);
    if (n == 0) return false;
    number.assign(text.substr(0, n));
    std::string_view rest = text.substr(n);
    if (!rest.empty() && rest[0] == ' ') rest.remove_prefix(1);
    unit.assign(rest);
    return true;
}

double to_si(const std::string &number, const Unit *unit) {
    double value = 0;
    if (!unit || unit->decimal_shift == 0) {
        read_double(number, value);
        return unit ? value * unit->factor : value;
    }
    // The prefix moves the decimal exponent: "12.5e1" mm is "12.5e-2" m, read once, so a file in
    // mm gives the very doubles of the same file in m.
    const size_t e = number.find_first_of("eE");
    long exponent = 0;
    if (e != std::string::npos) {
        const std::string digits = number.substr(e + 1);
        const bool minus = !digits.empty() && digits[0] == '-';
        for (char c : digits)
            if (c >= '0' && c <= '9' && exponent < 100000) exponent = 10 * exponent + (c - '0');
        if (minus) exponent = -exponent;
    }
    const std::string shifted =
        number.substr(0, e) + "e" + std::to_string(exponent + unit->decimal_shift);
    read_double(shifted, value);
    return value * unit->factor;
}

std::string units_for(const char *si) {
    std::string list;
    for (const Unit &u : kUnits)
        if (!std::strcmp(u.si, si)) list += (list.empty() ? "" : ", ") + std::string(u.name);
    return list.empty() ? std::string(si) : list;
}

}  // namespace stewart
