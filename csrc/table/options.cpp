// The option table (stewart/stewart_table.h) expanded: defaults, range checks, lookup and access.
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

template <class T> constexpr int is_integer_type() { return std::is_same<T, int>::value ? 1 : 0; }

#define INFO(id, name, type, unit, min, min_closed, max, max_closed, fallback, text)             \
    {id, #name, is_integer_type<type>(), unit, text, min, max, min_closed, max_closed, fallback},
const stewart_option_info kOptions[] = {STEWART_OPTION_TABLE(INFO)};
#undef INFO
constexpr int kOptionCount = sizeof kOptions / sizeof kOptions[0];

// The table lists every field of stewart_inverse_options, in order, with its type: a struct laid out
// from the table is the same struct.
struct Mirror {
#define FIELD(id, name, type, ...) type name;
    STEWART_OPTION_TABLE(FIELD)
#undef FIELD
};
static_assert(sizeof(Mirror) == sizeof(stewart_inverse_options), "STEWART_OPTION_TABLE lists every field");
#define SAME(id, name, type, ...)                                                                \
    static_assert(offsetof(Mirror, name) == offsetof(stewart_inverse_options, name) &&                   \
                      std::is_same<decltype(stewart_inverse_options::name), type>::value,                \
                  #name ": place and type as in stewart_inverse_options");
STEWART_OPTION_TABLE(SAME)
#undef SAME

// The message for option i's value outside its range. The tolerance's lower end is where the
// residual floors: its refusal says so.
stewart_status refuse(int i, double value, char *msg, size_t size) {
    const stewart_option_info &info = kOptions[i];
    if (!std::strcmp(info.name, "tolerance") && value > 0 && value < info.min)
        // The full level's max-norm position residual floors at 2.2e-16 (one rounding of
        // coordinates of order 1, in the platform's length unit): at or below that no pose ever
        // converges; 2.3e-16 still does, with up to 5 iterations.
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "tolerance = %s is below what the position residual can reach (about "
                           "2.2e-16, machine precision on the coordinates): use at least %s",
                           ExactText(value).c_str(), ExactText(info.min).c_str());
    char range[96];
    stewart::describe_range(info.min, info.min_closed, info.max, info.max_closed, range, sizeof range);
    return set_message(msg, size, STEWART_ERR_PARAMETER, "%s = %s must be %s (%s)", info.name,
                       ExactText(value).c_str(), range, info.description);
}

}  // namespace

extern "C" {

int stewart_option_count(void) { return kOptionCount; }

const stewart_option_info *stewart_option(int i) {
    return i >= 0 && i < kOptionCount ? &kOptions[i] : nullptr;
}

int stewart_option_find(const char *name) {
    for (int i = 0; name && i < kOptionCount; ++i)
        if (!std::strcmp(kOptions[i].name, name)) return i;
    return -1;
}

double stewart_option_get(const stewart_inverse_options *o, int i) {
    if (!o) return 0;
    int k = 0;
#define GET(id, name, ...)                                                                       \
    if (k++ == i) return static_cast<double>(o->name);
    STEWART_OPTION_TABLE(GET)
#undef GET
    return 0;
}

stewart_status stewart_option_set(stewart_inverse_options *o, int i, double value, char *msg,
                                  size_t size) {
    const stewart_option_info *info = stewart_option(i);
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
    int k = 0;
#define SET(id, name, type, ...)                                                                 \
    if (k++ == i) o->name = static_cast<type>(value);
    STEWART_OPTION_TABLE(SET)
#undef SET
    return stewart::clear_message(msg, size);
}

void stewart_inverse_options_default(stewart_inverse_options *o) {
    if (!o) return;
#define DEFAULT(id, name, type, unit, min, min_closed, max, max_closed, fallback, text)          \
    o->name = fallback;
    STEWART_OPTION_TABLE(DEFAULT)
#undef DEFAULT
}

stewart_status stewart_inverse_options_check(const stewart_inverse_options *o, char *msg, size_t size) {
    if (!o) return set_message(msg, size, STEWART_ERR_ARGUMENT, "options is NULL");
    // Every solve checks its options: the ranges are compile-time constants here.
    int i = 0;
#define CHECK(id, name, type, unit, min, min_closed, max, max_closed, fallback, text)            \
    if (!stewart::in_range(static_cast<double>(o->name), min, min_closed, max, max_closed))      \
        return refuse(i, static_cast<double>(o->name), msg, size);                               \
    ++i;
    STEWART_OPTION_TABLE(CHECK)
#undef CHECK
    if (!(o->singular_condition >= o->warn_condition))
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "condition limits warn = %s, singular = %s must satisfy "
                           "warn_condition <= singular_condition",
                           ExactText(o->warn_condition).c_str(),
                           ExactText(o->singular_condition).c_str());
    return stewart::clear_message(msg, size);
}

}  // extern "C"
