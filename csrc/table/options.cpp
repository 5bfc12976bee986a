// The option tables (stewart/stewart_table.h) expanded: defaults, range checks, lookup and access,
// one implementation for every direction's options.
#include "stewart/stewart_table.h"

#include <cmath>
#include <cstddef>
#include <cstring>
#include <type_traits>

#include "util/message.hpp"
#include "util/range.hpp"

using stewart::ExactText;
using stewart::set_message;

namespace {

// How an option is stored: a double, an int or a long (the plant's max_internal_steps).
enum class Storage { real, int_, long_ };
template <class T>
constexpr Storage storage_of() {
    return std::is_same<T, int>::value    ? Storage::int_
           : std::is_same<T, long>::value ? Storage::long_
                                          : Storage::real;
}
template <class T>
constexpr int is_integer_type() {
    return storage_of<T>() != Storage::real;
}

// Where an option of a table lives in its struct.
struct Field {
    size_t offset;
    Storage storage;
};

// The rules of a table across its fields, checked once every option is in its range: OK, or the
// message of the first broken.
using Rules = stewart_status (*)(const void *options, char *msg, size_t size);

// A table expanded: the options' descriptions and places, and its rules across fields (or none).
struct Table {
    const stewart_option_info *info;
    const Field *field;
    int count;
    Rules rules;
};

// The inverse and forward solvers': warn_condition <= singular_condition.
template <class Options>
stewart_status conditions_in_order(const void *options, char *msg, size_t size) {
    const Options &o = *static_cast<const Options *>(options);
    if (!(o.singular_condition >= o.warn_condition))
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "condition limits warn = %s, singular = %s must satisfy "
                           "warn_condition <= singular_condition",
                           ExactText(o.warn_condition).c_str(),
                           ExactText(o.singular_condition).c_str());
    return STEWART_OK;
}

// The plant's: fixed steps only for an explicit method (the implicit ones need their error
// control).
stewart_status fixed_steps_explicit(const void *options, char *msg, size_t size) {
    const stewart_plant_options &o = *static_cast<const stewart_plant_options *>(options);
    if (o.fixed_steps > 0 && o.method != STEWART_PLANT_ERK && o.method != STEWART_PLANT_ERK5)
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "fixed_steps = %d needs method 2 or 3 (explicit Runge-Kutta), not %d",
                           o.fixed_steps, o.method);
    return STEWART_OK;
}

#define INFO(id, name, type, unit, min, min_closed, max, max_closed, fallback, text) \
    {id, #name, is_integer_type<type>(), unit, text, min, max, min_closed, max_closed, fallback},
#define INVERSE_FIELD(id, name, type, ...) \
    {offsetof(stewart_inverse_options, name), storage_of<type>()},
#define FORWARD_FIELD(id, name, type, ...) \
    {offsetof(stewart_forward_options, name), storage_of<type>()},
#define PLANT_FIELD(id, name, type, ...) \
    {offsetof(stewart_plant_options, name), storage_of<type>()},
#define LINEARIZE_FIELD(id, name, type, ...) \
    {offsetof(stewart_linearize_options, name), storage_of<type>()},
#define LIMITS_FIELD(id, name, type, ...) \
    {offsetof(stewart_limits_options, name), storage_of<type>()},
#define CUEING_FIELD(id, name, type, ...) \
    {offsetof(stewart_cueing_options, name), storage_of<type>()},
const stewart_option_info kInverseInfo[] = {STEWART_OPTION_TABLE(INFO)};
const Field kInverseFields[] = {STEWART_OPTION_TABLE(INVERSE_FIELD)};
const stewart_option_info kForwardInfo[] = {STEWART_FORWARD_OPTION_TABLE(INFO)};
const Field kForwardFields[] = {STEWART_FORWARD_OPTION_TABLE(FORWARD_FIELD)};
const stewart_option_info kPlantInfo[] = {STEWART_PLANT_OPTION_TABLE(INFO)};
const Field kPlantFields[] = {STEWART_PLANT_OPTION_TABLE(PLANT_FIELD)};
const stewart_option_info kLinearizeInfo[] = {STEWART_LINEARIZE_OPTION_TABLE(INFO)};
const Field kLinearizeFields[] = {STEWART_LINEARIZE_OPTION_TABLE(LINEARIZE_FIELD)};
const stewart_option_info kLimitsInfo[] = {STEWART_LIMITS_OPTION_TABLE(INFO)};
const Field kLimitsFields[] = {STEWART_LIMITS_OPTION_TABLE(LIMITS_FIELD)};
const stewart_option_info kCueingInfo[] = {STEWART_CUEING_OPTION_TABLE(INFO)};
const Field kCueingFields[] = {STEWART_CUEING_OPTION_TABLE(CUEING_FIELD)};
#undef INFO
#undef INVERSE_FIELD
#undef FORWARD_FIELD
#undef PLANT_FIELD
#undef LINEARIZE_FIELD
#undef LIMITS_FIELD
#undef CUEING_FIELD
template <size_t n>
constexpr Table table_of(const stewart_option_info (&info)[n], const Field *field,
                         Rules rules = nullptr) {
    return {info, field, static_cast<int>(n), rules};
}
const Table kInverse =
    table_of(kInverseInfo, kInverseFields, conditions_in_order<stewart_inverse_options>);
const Table kForward =
    table_of(kForwardInfo, kForwardFields, conditions_in_order<stewart_forward_options>);
const Table kPlant = table_of(kPlantInfo, kPlantFields, fixed_steps_explicit);
const Table kLinearize = table_of(kLinearizeInfo, kLinearizeFields);
const Table kLimits = table_of(kLimitsInfo, kLimitsFields);
const Table kCueing = table_of(kCueingInfo, kCueingFields);

// Each table lists every field of its struct, in order, with its type: a struct laid out from the
// table is the same struct.
#define FIELD(id, name, type, ...) type name;
struct InverseMirror {
    STEWART_OPTION_TABLE(FIELD)
};
struct ForwardMirror {
    STEWART_FORWARD_OPTION_TABLE(FIELD)
};
struct PlantMirror {
    STEWART_PLANT_OPTION_TABLE(FIELD)
};
struct LinearizeMirror {
    STEWART_LINEARIZE_OPTION_TABLE(FIELD)
};
struct LimitsMirror {
    STEWART_LIMITS_OPTION_TABLE(FIELD)
};
struct CueingMirror {
    STEWART_CUEING_OPTION_TABLE(FIELD)
};
#undef FIELD
static_assert(sizeof(InverseMirror) == sizeof(stewart_inverse_options),
              "STEWART_OPTION_TABLE lists every field");
static_assert(sizeof(ForwardMirror) == sizeof(stewart_forward_options),
              "STEWART_FORWARD_OPTION_TABLE lists every field");
static_assert(sizeof(PlantMirror) == sizeof(stewart_plant_options),
              "STEWART_PLANT_OPTION_TABLE lists every field");
static_assert(sizeof(LinearizeMirror) == sizeof(stewart_linearize_options),
              "STEWART_LINEARIZE_OPTION_TABLE lists every field");
static_assert(sizeof(LimitsMirror) == sizeof(stewart_limits_options),
              "STEWART_LIMITS_OPTION_TABLE lists every field");
static_assert(sizeof(CueingMirror) == sizeof(stewart_cueing_options),
              "STEWART_CUEING_OPTION_TABLE lists every field");
#define SAME(Options, Mirror, name, type)                                 \
    static_assert(offsetof(Mirror, name) == offsetof(Options, name) &&    \
                      std::is_same<decltype(Options::name), type>::value, \
                  #name ": place and type as in " #Options);
#define SAME_INVERSE(id, name, type, ...) SAME(stewart_inverse_options, InverseMirror, name, type)
#define SAME_FORWARD(id, name, type, ...) SAME(stewart_forward_options, ForwardMirror, name, type)
#define SAME_PLANT(id, name, type, ...) SAME(stewart_plant_options, PlantMirror, name, type)
#define SAME_LINEARIZE(id, name, type, ...) \
    SAME(stewart_linearize_options, LinearizeMirror, name, type)
#define SAME_LIMITS(id, name, type, ...) SAME(stewart_limits_options, LimitsMirror, name, type)
#define SAME_CUEING(id, name, type, ...) SAME(stewart_cueing_options, CueingMirror, name, type)
STEWART_OPTION_TABLE(SAME_INVERSE)
STEWART_FORWARD_OPTION_TABLE(SAME_FORWARD)
STEWART_PLANT_OPTION_TABLE(SAME_PLANT)
STEWART_LINEARIZE_OPTION_TABLE(SAME_LINEARIZE)
STEWART_LIMITS_OPTION_TABLE(SAME_LIMITS)
STEWART_CUEING_OPTION_TABLE(SAME_CUEING)
#undef SAME_INVERSE
#undef SAME_FORWARD
#undef SAME_PLANT
#undef SAME_LINEARIZE
#undef SAME_LIMITS
#undef SAME_CUEING
#undef SAME

const stewart_option_info *option(const Table &t, int i) {
    return i >= 0 && i < t.count ? &t.info[i] : nullptr;
}

int find(const Table &t, const char *name) {
    for (int i = 0; name && i < t.count; ++i)
        if (!std::strcmp(t.info[i].name, name)) return i;
    return -1;
}

template <class T>
T load(const char *at) {
    T v;
    std::memcpy(&v, at, sizeof v);
    return v;
}

template <class T>
void store(char *at, T v) {
    std::memcpy(at, &v, sizeof v);
}

double get(const Table &t, const void *o, int i) {
    const char *at = static_cast<const char *>(o) + t.field[i].offset;
    switch (t.field[i].storage) {
        case Storage::int_: return load<int>(at);
        case Storage::long_: return static_cast<double>(load<long>(at));
        case Storage::real: break;
    }
    return load<double>(at);
}

// Stores a value that set() has checked: in range, and whole for an integer option (every
// integer range fits an int).
void put(const Table &t, void *o, int i, double value) {
    char *at = static_cast<char *>(o) + t.field[i].offset;
    switch (t.field[i].storage) {
        case Storage::int_: return store(at, static_cast<int>(value));
        case Storage::long_: return store(at, static_cast<long>(value));
        case Storage::real: return store(at, value);
    }
}

// The message for option i's value outside its range. The lower ends of the inverse and forward
// tolerance and of the plant's absolute tolerance are numerical floors: their refusals say so.
stewart_status refuse(const Table &t, int i, double value, char *msg, size_t size) {
    const stewart_option_info &info = t.info[i];
    if (!std::strcmp(info.name, "tolerance") && value > 0 && value < info.min)
        // The full level's max-norm position residual floors at 2.2e-16 (one rounding of
        // coordinates of order 1, in the platform's length unit): at or below that no pose ever
        // converges; 2.3e-16 still does, with up to 5 iterations.
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "tolerance = %s is below what the position residual can reach (about "
                           "2.2e-16, machine precision on the coordinates): use at least %s",
                           ExactText(value).c_str(), ExactText(info.min).c_str());
    if (!std::strcmp(info.name, "absolute_tolerance"))
        // A plant's first step at rest fails below 3e-26 (full level, ERK 5(4); 1.3e-26 ERK 4(3),
        // 6.7e-28 Adams; 1e-156 massless), found by bisection: the floor keeps a margin.
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "absolute_tolerance = %s must be >= %s and finite (below it the "
                           "integrators' error test fails on rounding alone)",
                           ExactText(value).c_str(), ExactText(info.min).c_str());
    char range[96];
    stewart::describe_range(info.min, info.min_closed, info.max, info.max_closed, range,
                            sizeof range);
    return set_message(msg, size, STEWART_ERR_PARAMETER, "%s = %s must be %s (%s)", info.name,
                       ExactText(value).c_str(), range, info.description);
}

stewart_status set(const Table &t, void *o, int i, double value, char *msg, size_t size) {
    const stewart_option_info *info = option(t, i);
    if (!o || !info) return set_message(msg, size, STEWART_ERR_ARGUMENT, "no option %d", i);
    if (!stewart::in_range(value, info->min, info->min_closed, info->max, info->max_closed) ||
        (info->is_integer && value != std::floor(value))) {
        char range[96];
        stewart::describe_range(info->min, info->min_closed, info->max, info->max_closed, range,
                                sizeof range);
        return set_message(msg, size, STEWART_ERR_PARAMETER, "%s = %s must be %s%s", info->name,
                           ExactText(value).c_str(), info->is_integer ? "a whole number " : "",
                           range);
    }
    put(t, o, i, value);
    return stewart::clear_message(msg, size);
}

void defaults(const Table &t, void *o) {
    for (int i = 0; i < t.count; ++i) put(t, o, i, t.info[i].default_value);
}

// Every option in its table's range, in the table's order, then the table's rules across fields.
stewart_status check(const Table &t, const void *o, char *msg, size_t size) {
    if (!o) return set_message(msg, size, STEWART_ERR_ARGUMENT, "options is NULL");
    for (int i = 0; i < t.count; ++i) {
        const stewart_option_info &info = t.info[i];
        const double v = get(t, o, i);
        if (!stewart::in_range(v, info.min, info.min_closed, info.max, info.max_closed))
            return refuse(t, i, v, msg, size);
    }
    if (t.rules) {
        const stewart_status s = t.rules(o, msg, size);
        if (s != STEWART_OK) return s;
    }
    return stewart::clear_message(msg, size);
}

}  // namespace

// The C API of one direction's option table, the same over every table:
// stewart_<direction>_option_count, _option, _option_find, _option_get, _option_set and
// _options_check; and _options_default (the plant's is in plant_api.cpp).
#define OPTION_TABLE_API(direction, table)                                                      \
    int stewart_##direction##_option_count(void) { return table.count; }                        \
    const stewart_option_info *stewart_##direction##_option(int i) { return option(table, i); } \
    int stewart_##direction##_option_find(const char *name) { return find(table, name); }       \
    double stewart_##direction##_option_get(const stewart_##direction##_options *o, int i) {    \
        return o && option(table, i) ? get(table, o, i) : 0;                                    \
    }                                                                                           \
    stewart_status stewart_##direction##_option_set(stewart_##direction##_options *o, int i,    \
                                                    double value, char *msg, size_t size) {     \
        return set(table, o, i, value, msg, size);                                              \
    }                                                                                           \
    stewart_status stewart_##direction##_options_check(const stewart_##direction##_options *o,  \
                                                       char *msg, size_t size) {                \
        return check(table, o, msg, size);                                                      \
    }
#define OPTION_TABLE_DEFAULTS(direction, table)                                    \
    void stewart_##direction##_options_default(stewart_##direction##_options *o) { \
        if (o) defaults(table, o);                                                 \
    }

extern "C" {

OPTION_TABLE_API(inverse, kInverse)
OPTION_TABLE_DEFAULTS(inverse, kInverse)
OPTION_TABLE_API(forward, kForward)
OPTION_TABLE_DEFAULTS(forward, kForward)
OPTION_TABLE_API(plant, kPlant)
OPTION_TABLE_API(linearize, kLinearize)
OPTION_TABLE_DEFAULTS(linearize, kLinearize)
OPTION_TABLE_API(limits, kLimits)
OPTION_TABLE_DEFAULTS(limits, kLimits)

OPTION_TABLE_API(cueing, kCueing)
OPTION_TABLE_DEFAULTS(cueing, kCueing)

}  // extern "C"
