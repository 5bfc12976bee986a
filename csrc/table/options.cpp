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
template <class T> constexpr Storage storage_of() {
    return std::is_same<T, int>::value    ? Storage::int_
           : std::is_same<T, long>::value ? Storage::long_
                                          : Storage::real;
}
template <class T> constexpr int is_integer_type() { return storage_of<T>() != Storage::real; }

// Where an option of a table lives in its struct.
struct Field {
    size_t offset;
    Storage storage;
};

// A table expanded: the options' descriptions and places.
struct Table {
    const stewart_option_info *info;
    const Field *field;
    int count;
};

#define INFO(id, name, type, unit, min, min_closed, max, max_closed, fallback, text)             \
    {id, #name, is_integer_type<type>(), unit, text, min, max, min_closed, max_closed, fallback},
#define INVERSE_FIELD(id, name, type, ...) {offsetof(stewart_inverse_options, name), storage_of<type>()},
#define FORWARD_FIELD(id, name, type, ...) {offsetof(stewart_forward_options, name), storage_of<type>()},
#define PLANT_FIELD(id, name, type, ...) {offsetof(stewart_plant_options, name), storage_of<type>()},
#define LINEARIZE_FIELD(id, name, type, ...) {offsetof(stewart_linearize_options, name), storage_of<type>()},
#define LIMITS_FIELD(id, name, type, ...) {offsetof(stewart_limits_options, name), storage_of<type>()},
#define CUEING_FIELD(id, name, type, ...) {offsetof(stewart_cueing_options, name), storage_of<type>()},
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
template <size_t n> constexpr Table table_of(const stewart_option_info (&info)[n], const Field *field) {
    return {info, field, static_cast<int>(n)};
}
const Table kInverse = table_of(kInverseInfo, kInverseFields);
const Table kForward = table_of(kForwardInfo, kForwardFields);
const Table kPlant = table_of(kPlantInfo, kPlantFields);
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
#define SAME(Options, Mirror, name, type)                                                        \
    static_assert(offsetof(Mirror, name) == offsetof(Options, name) &&                           \
                      std::is_same<decltype(Options::name), type>::value,                        \
                  #name ": place and type as in " #Options);
#define SAME_INVERSE(id, name, type, ...) SAME(stewart_inverse_options, InverseMirror, name, type)
#define SAME_FORWARD(id, name, type, ...) SAME(stewart_forward_options, ForwardMirror, name, type)
#define SAME_PLANT(id, name, type, ...) SAME(stewart_plant_options, PlantMirror, name, type)
#define SAME_LINEARIZE(id, name, type, ...)                                                      \
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

template <class T> T load(const char *at) {
    T v;
    std::memcpy(&v, at, sizeof v);
    return v;
}

template <class T> void store(char *at, T v) { std::memcpy(at, &v, sizeof v); }

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
    stewart::describe_range(info.min, info.min_closed, info.max, info.max_closed, range, sizeof range);
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

// Every option in its table's range, in the table's order.
stewart_status check_ranges(const Table &t, const void *o, char *msg, size_t size) {
    if (!o) return set_message(msg, size, STEWART_ERR_ARGUMENT, "options is NULL");
    for (int i = 0; i < t.count; ++i) {
        const stewart_option_info &info = t.info[i];
        const double v = get(t, o, i);
        if (!stewart::in_range(v, info.min, info.min_closed, info.max, info.max_closed))
            return refuse(t, i, v, msg, size);
    }
    return stewart::clear_message(msg, size);
}

// Every option in its range, and warn_condition <= singular_condition.
stewart_status check(const Table &t, const void *o, double warn_condition,
                     double singular_condition, char *msg, size_t size) {
    const stewart_status ranges = check_ranges(t, o, msg, size);
    if (ranges != STEWART_OK) return ranges;
    if (!(singular_condition >= warn_condition))
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "condition limits warn = %s, singular = %s must satisfy "
                           "warn_condition <= singular_condition",
                           ExactText(warn_condition).c_str(), ExactText(singular_condition).c_str());
    return stewart::clear_message(msg, size);
}

}  // namespace

extern "C" {

int stewart_inverse_option_count(void) { return kInverse.count; }
const stewart_option_info *stewart_inverse_option(int i) { return option(kInverse, i); }
int stewart_inverse_option_find(const char *name) { return find(kInverse, name); }
double stewart_inverse_option_get(const stewart_inverse_options *o, int i) {
    return o && option(kInverse, i) ? get(kInverse, o, i) : 0;
}
stewart_status stewart_inverse_option_set(stewart_inverse_options *o, int i, double value,
                                          char *msg, size_t size) {
    return set(kInverse, o, i, value, msg, size);
}
void stewart_inverse_options_default(stewart_inverse_options *o) {
    if (o) defaults(kInverse, o);
}
stewart_status stewart_inverse_options_check(const stewart_inverse_options *o, char *msg,
                                             size_t size) {
    return check(kInverse, o, o ? o->warn_condition : 0, o ? o->singular_condition : 0, msg,
                 size);
}

int stewart_forward_option_count(void) { return kForward.count; }
const stewart_option_info *stewart_forward_option(int i) { return option(kForward, i); }
int stewart_forward_option_find(const char *name) { return find(kForward, name); }
double stewart_forward_option_get(const stewart_forward_options *o, int i) {
    return o && option(kForward, i) ? get(kForward, o, i) : 0;
}
stewart_status stewart_forward_option_set(stewart_forward_options *o, int i, double value,
                                          char *msg, size_t size) {
    return set(kForward, o, i, value, msg, size);
}
void stewart_forward_options_default(stewart_forward_options *o) {
    if (o) defaults(kForward, o);
}
stewart_status stewart_forward_options_check(const stewart_forward_options *o, char *msg,
                                             size_t size) {
    return check(kForward, o, o ? o->warn_condition : 0, o ? o->singular_condition : 0, msg,
                 size);
}

int stewart_plant_option_count(void) { return kPlant.count; }
const stewart_option_info *stewart_plant_option(int i) { return option(kPlant, i); }
int stewart_plant_option_find(const char *name) { return find(kPlant, name); }
double stewart_plant_option_get(const stewart_plant_options *o, int i) {
    return o && option(kPlant, i) ? get(kPlant, o, i) : 0;
}
stewart_status stewart_plant_option_set(stewart_plant_options *o, int i, double value, char *msg,
                                        size_t size) {
    return set(kPlant, o, i, value, msg, size);
}
// Every option in its range, and fixed steps only for an explicit method (the implicit ones
// need their error control).
stewart_status stewart_plant_options_check(const stewart_plant_options *o, char *msg,
                                           size_t size) {
    const stewart_status ranges = check_ranges(kPlant, o, msg, size);
    if (ranges != STEWART_OK) return ranges;
    if (o->fixed_steps > 0 && o->method != STEWART_PLANT_ERK && o->method != STEWART_PLANT_ERK5)
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "fixed_steps = %d needs method 2 or 3 (explicit Runge-Kutta), not %d",
                           o->fixed_steps, o->method);
    return stewart::clear_message(msg, size);
}

int stewart_linearize_option_count(void) { return kLinearize.count; }
const stewart_option_info *stewart_linearize_option(int i) { return option(kLinearize, i); }
int stewart_linearize_option_find(const char *name) { return find(kLinearize, name); }
double stewart_linearize_option_get(const stewart_linearize_options *o, int i) {
    return o && option(kLinearize, i) ? get(kLinearize, o, i) : 0;
}
stewart_status stewart_linearize_option_set(stewart_linearize_options *o, int i, double value,
                                            char *msg, size_t size) {
    return set(kLinearize, o, i, value, msg, size);
}
void stewart_linearize_options_default(stewart_linearize_options *o) {
    if (o) defaults(kLinearize, o);
}
stewart_status stewart_linearize_options_check(const stewart_linearize_options *o, char *msg,
                                               size_t size) {
    return check_ranges(kLinearize, o, msg, size);
}

int stewart_limits_option_count(void) { return kLimits.count; }
const stewart_option_info *stewart_limits_option(int i) { return option(kLimits, i); }
int stewart_limits_option_find(const char *name) { return find(kLimits, name); }
double stewart_limits_option_get(const stewart_limits_options *o, int i) {
    return o && option(kLimits, i) ? get(kLimits, o, i) : 0;
}
stewart_status stewart_limits_option_set(stewart_limits_options *o, int i, double value,
                                         char *msg, size_t size) {
    return set(kLimits, o, i, value, msg, size);
}
void stewart_limits_options_default(stewart_limits_options *o) {
    if (o) defaults(kLimits, o);
}
stewart_status stewart_limits_options_check(const stewart_limits_options *o, char *msg,
                                            size_t size) {
    return check_ranges(kLimits, o, msg, size);
}

int stewart_cueing_option_count(void) { return kCueing.count; }
const stewart_option_info *stewart_cueing_option(int i) { return option(kCueing, i); }
int stewart_cueing_option_find(const char *name) { return find(kCueing, name); }
double stewart_cueing_option_get(const stewart_cueing_options *o, int i) {
    return o && option(kCueing, i) ? get(kCueing, o, i) : 0;
}
stewart_status stewart_cueing_option_set(stewart_cueing_options *o, int i, double value,
                                         char *msg, size_t size) {
    return set(kCueing, o, i, value, msg, size);
}
void stewart_cueing_options_default(stewart_cueing_options *o) {
    if (o) defaults(kCueing, o);
}
stewart_status stewart_cueing_options_check(const stewart_cueing_options *o, char *msg,
                                            size_t size) {
    return check_ranges(kCueing, o, msg, size);
}

}  // extern "C"
