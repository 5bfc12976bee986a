// The units a platform file may write its numbers in (docs/geometry.md, section 3): lengths and
// angles in the units of a datasheet, converted to the parameter table's SI units at read time.
#pragma once

#include <string>
#include <string_view>

namespace stewart {

struct Unit {
    const char *name;   // as written in a file: "mm", "deg"
    const char *si;     // the SI unit it converts to: "m" or "rad"
    int decimal_shift;  // a power-of-ten prefix: the number's exponent moves by it (exact)
    double factor;      // then multiplied by this (1 for m, mm, rad, ...; pi/180 for deg)
    double per_si;      // what an SI value is multiplied by to be in this unit (printing)
};

// The unit named `name` (any of "m cm mm um µm nm in rad mrad urad µrad deg"), or nullptr.
const Unit *find_unit(std::string_view name);

// The units a file states for all its lengths and angles ("units": {...}); nullptr: SI.
struct FileUnits {
    const Unit *length = nullptr;
    const Unit *angle = nullptr;
};

// "12.5 mm" (or "12.5mm", "12.5"): the number's text and the unit's name ("" if none); false if
// the text does not start with a JSON number.
bool split_quantity(std::string_view text, std::string &number, std::string &unit);

// The length of the JSON number at the start of text (-?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?
// [0-9]+)?), or 0 if there is none.
size_t json_number_length(std::string_view text);

// number (JSON syntax) in unit, in SI: the decimal prefix applied to the exponent, so that
// "12.5 mm" reads as the very double "0.0125" does. unit nullptr: SI already.
double to_si(const std::string &number, const Unit *unit);

// The units written for an element whose SI unit is si ("m", "rad", "kg", ...): a comma list for
// messages.
std::string units_for(const char *si);

}  // namespace stewart
