// Platform files (stewart/stewart_platform_file.h): the fields of the JSON subset
// (table/json_fields.hpp) put into the parameters, each element checked against the parameter
// table and given once, in the file's units (table/units.hpp) converted to SI.
#include "stewart/stewart_platform_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <string>
#include <system_error>
#include <vector>

#include "stewart/stewart_table.h"
#include "table/json_fields.hpp"
#include "table/units.hpp"
#include "util/message.hpp"
#include "util/range.hpp"

using stewart::set_message;

namespace {

using stewart::JsonField;
using stewart::JsonItem;
using stewart::JsonValue;

// A name a file may give: a parameter of the table, or one of the strokes' other form
// (stroke_neutral, stroke_travel: per leg, converted to stroke_min and stroke_max at read).
struct Target {
    const char *name;
    int count;
    bool fills;  // one number given by the bare name fills every element
    int param;   // the table's index, or -1
    double *values;
    std::vector<int> owner;  // the field that gave each element, or -1
};

// "name = [1, 2, 3]" or "name = 0.5": a value as the file gave it, for messages.
std::string shown(const JsonField &f) {
    auto item = [](const JsonItem &x) { return x.quoted ? "\"" + x.text + "\"" : x.text; };
    if (f.value.kind == JsonValue::Text) return "\"" + f.value.text + "\"";
    if (f.value.kind == JsonValue::Object) return "{...}";
    if (f.value.kind == JsonValue::Number) return item(f.value.items[0]);
    std::string s = "[";
    for (size_t i = 0; i < f.value.items.size(); ++i) s += (i ? ", " : "") + item(f.value.items[i]);
    return s + "]";
}

std::string element_name(const Target &t, int e) {
    return t.count == 1 ? std::string(t.name)
                        : std::string(t.name) + "[" + std::to_string(e + 1) + "]";
}

const char *element_unit(const Target &t, int e) {
    return t.param >= 0 ? stewart_param_element_unit(t.param, e) : "m";
}

// The target of a field's name with the element it names (-1: the whole target), or nullptr.
Target *find_target(std::vector<Target> &targets, const std::string &name, int &element) {
    const size_t bracket = name.find('[');
    const std::string base = name.substr(0, bracket);
    for (Target &t : targets) {
        if (base != t.name) continue;
        element = -1;
        if (bracket == std::string::npos) return &t;
        if (t.param >= 0) {  // the table's own spelling of an element ("gravity[3]")
            int e = 0;
            return stewart_param_find(name.c_str(), &e) == t.param ? (element = e, &t) : nullptr;
        }
        const std::string index = name.substr(bracket);
        for (int e = 0; e < t.count; ++e)
            if (index == "[" + std::to_string(e + 1) + "]") return element = e, &t;
        return nullptr;
    }
    return nullptr;
}

// One item in SI for an element of SI unit si: a number in the file's units, or "12.5 mm".
bool item_value(const JsonItem &x, const char *si, const stewart::FileUnits &units,
                const std::string &what, double &out, std::string &why) {
    const bool length = !std::strcmp(si, "m"), angle = !std::strcmp(si, "rad");
    if (!x.quoted) {
        out = stewart::to_si(x.text, length ? units.length : angle ? units.angle : nullptr);
    } else {
        std::string number, unit;
        if (!stewart::split_quantity(x.text, number, unit) || unit.empty())
            return why = what + " = \"" + x.text +
                         "\" must be a number, or a number and its unit "
                         "(\"12.5 mm\")",
                   false;
        const stewart::Unit *u = stewart::find_unit(unit);
        const bool same_kind = u && !std::strcmp(u->si, si);
        if (!same_kind && unit != si)
            return why = what + " = \"" + x.text + "\": " + unit + " is not a unit of " + what +
                         " [" + si + "]; write it in " + stewart::units_for(si),
                   false;
        out = stewart::to_si(number, same_kind ? u : nullptr);
    }
    if (!std::isfinite(out))
        return why = what + " = " + x.text + " is not a finite double in SI", false;
    return true;
}

// Whether the file wrote x in other units than the element's SI ones.
bool converted(const JsonItem &x, const char *si, const stewart::FileUnits &units) {
    return x.quoted || (!std::strcmp(si, "m") && units.length) ||
           (!std::strcmp(si, "rad") && units.angle);
}

// Puts field f (the index-th) into its target's elements, each checked against the table and
// given once whatever the spelling ("gravity", "gravity[3]"); false with the message in why.
bool apply(const std::vector<JsonField> &fields, int index, std::vector<Target> &targets,
           const stewart::FileUnits &units, std::string &why) {
    const JsonField &f = fields[static_cast<size_t>(index)];
    int element = -1;
    Target *t = find_target(targets, f.name, element);
    if (!t) {  // not a name a file may give: the library names the nearest
        char message[STEWART_MESSAGE_SIZE];
        stewart_params scratch;
        stewart_params_default(&scratch);
        stewart_params_set(&scratch, f.name.c_str(), 0.0, message, sizeof message);
        return why = message, false;
    }
    const bool whole = element < 0;
    const JsonValue &v = f.value;
    if (v.kind == JsonValue::Object) return why = f.name + ": objects are not values here", false;
    if (v.kind == JsonValue::List) {
        if (!whole || t->count == 1)
            return why = f.name + " = " + shown(f) + " must be one number", false;
        if (static_cast<int>(v.items.size()) != t->count)
            return why = f.name + " has " + std::to_string(v.items.size()) + " values: it needs " +
                         std::to_string(t->count) + ", " + f.name + "[1].." + f.name + "[" +
                         std::to_string(t->count) + "]",
                   false;
    } else if (whole && t->count > 1 && !t->fills) {
        return why = f.name + " = " + shown(f) + " must be a list of its " +
                     std::to_string(t->count) + " values",
               false;
    }
    const JsonItem single{
        v.kind == JsonValue::Text     ? v.text
        : v.kind == JsonValue::Number ? v.items[0].text
                                      : "",
        v.kind == JsonValue::Text || (v.kind == JsonValue::Number && v.items[0].quoted)};
    const int first = whole ? 0 : element, last = whole ? t->count : element + 1;
    for (int e = first; e < last; ++e) {
        const JsonItem &x = v.kind == JsonValue::List ? v.items[static_cast<size_t>(e)] : single;
        const std::string name = element_name(*t, e);
        double value = 0;
        if (!item_value(x, element_unit(*t, e), units, name, value, why)) return false;
        char message[STEWART_MESSAGE_SIZE];
        if (t->param >= 0 &&
            stewart_param_check_value(t->param, e, value, message, sizeof message) != STEWART_OK)
            return why = std::string(message) + (converted(x, element_unit(*t, e), units)
                                                     ? " (the file's " + x.text + ")"
                                                     : ""),
                   false;
        const int owner = t->owner[static_cast<size_t>(e)];
        if (owner >= 0)
            return why = name + " is given twice: by \"" + fields[static_cast<size_t>(owner)].name +
                         "\" at line " + std::to_string(fields[static_cast<size_t>(owner)].line) +
                         " and by \"" + f.name + "\"",
                   false;
        t->owner[static_cast<size_t>(e)] = index;
        t->values[e] = value;
    }
    return true;
}

// "units": {"length": "mm", "angle": "deg"}: the units of every number the file writes without
// one whose parameter is in m or rad.
bool read_file_units(const JsonField &f, stewart::FileUnits &units, std::string &why) {
    if (f.value.kind != JsonValue::Object)
        return why = "units = " + shown(f) +
                     " must be an object: {\"length\": \"mm\", \"angle\": "
                     "\"deg\"}",
               false;
    for (const auto &m : f.value.members) {
        const bool length = m.first == "length";
        if (!length && m.first != "angle")
            return why = "units." + m.first +
                         ": a file gives the units of \"length\" and "
                         "\"angle\" only (masses, inertias and gravity are SI: kg, kg.m2, m/s2)",
                   false;
        const char *si = length ? "m" : "rad";
        const stewart::Unit *u = stewart::find_unit(m.second);
        if (!u || std::strcmp(u->si, si))
            return why = "units." + m.first + " = \"" + m.second + "\" is not a unit of " +
                         m.first + ": one of " + stewart::units_for(si),
                   false;
        (length ? units.length : units.angle) = u;
    }
    return true;
}

int first_owner(const Target &t) {
    for (int o : t.owner)
        if (o >= 0) return o;
    return -1;
}

// Where a cross-field problem is: the field's line and column, and the message.
struct Problem {
    int field = -1;
    std::string why;
};

// stroke_neutral ± stroke_travel, if the file gives them, into stroke_min and stroke_max.
bool strokes_from_travel(const std::vector<JsonField> &fields, std::vector<Target> &targets,
                         Target &lo, Target &hi, Problem &p) {
    Target &neutral = targets[targets.size() - 2], &travel = targets.back();
    const int n = first_owner(neutral), t = first_owner(travel);
    const int given = n < 0 ? t : t < 0 ? n : std::min(n, t);  // the first field of the two
    if (given < 0) return true;
    p.field = given;
    const int absolute = std::max(first_owner(lo), first_owner(hi));
    if (absolute >= 0)
        return p.why = "the strokes are given twice, as \"" +
                       fields[static_cast<size_t>(absolute)].name + "\" (line " +
                       std::to_string(fields[static_cast<size_t>(absolute)].line) + ") and as \"" +
                       fields[static_cast<size_t>(given)].name +
                       "\": give stroke_min and stroke_max, or stroke_neutral and stroke_travel",
               false;
    for (const Target *t : {&neutral, &travel})
        for (int e = 0; e < t->count; ++e)
            if (t->owner[static_cast<size_t>(e)] < 0)
                return p.why = "the file gives \"" + fields[static_cast<size_t>(given)].name +
                               "\" but not " + element_name(*t, e) +
                               ": stroke_neutral and "
                               "stroke_travel go together, for every leg",
                       false;
    char message[STEWART_MESSAGE_SIZE];
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const std::string leg = "[" + std::to_string(k + 1) + "]";
        if (!(travel.values[k] > 0))
            return p.why = "stroke_travel" + leg + " = " +
                           stewart::ExactText(travel.values[k]).c_str() + " m must be > 0: leg " +
                           std::to_string(k + 1) + " moves stroke_neutral ± stroke_travel",
                   false;
        const double ends[2] = {neutral.values[k] - travel.values[k],
                                neutral.values[k] + travel.values[k]};
        for (int end = 0; end < 2; ++end) {
            Target &to = end ? hi : lo;
            if (stewart_param_check_value(to.param, k, ends[end], message, sizeof message) !=
                STEWART_OK)
                return p.why = std::string("stroke_neutral") + leg + (end ? " + " : " - ") +
                               "stroke_travel" + leg + ": " + message,
                       false;
            to.values[k] = ends[end];
            to.owner[static_cast<size_t>(k)] = given;
        }
    }
    return true;
}

// Joints only with geometry 1, and then every coordinate of both sides from the file.
bool joints_complete(const std::vector<JsonField> &fields, const Target &geometry,
                     const Target &base, const Target &platform, Problem &p) {
    const int base_field = first_owner(base), platform_field = first_owner(platform);
    const bool one = first_owner(geometry) >= 0 && geometry.values[0] == 1.0;
    if (!one && (base_field >= 0 || platform_field >= 0)) {
        p.field = base_field >= 0 ? base_field : platform_field;
        p.why = std::string("the file gives ") + fields[static_cast<size_t>(p.field)].name +
                " but not geometry = 1: the joints would be ignored (geometry 0 places them on "
                "the circles)";
        return false;
    }
    if (!one) return true;
    p.field = first_owner(geometry);
    for (const Target *side : {&base, &platform}) {
        int missing = 0, first = -1;
        for (int e = 0; e < side->count; ++e)
            if (side->owner[static_cast<size_t>(e)] < 0)
                missing += 1, first = first < 0 ? e : first;
        if (missing == side->count)
            return p.why = std::string("the file gives geometry = 1 but not ") + side->name +
                           ": a platform file gives all its joints",
                   false;
        if (missing > 0)
            return p.why =
                       std::string("the file gives geometry = 1 and only some of ") + side->name +
                       ": " + element_name(*side, first) +
                       (missing > 1 ? " and " + std::to_string(missing - 1) + " more are" : " is") +
                       " missing; with geometry 1 a file gives every joint coordinate",
                   false;
    }
    return true;
}

std::vector<Target> make_targets(stewart_params &params, double *neutral, double *travel) {
    std::vector<Target> targets;
    for (int i = 0; i < stewart_param_count(); ++i) {
        const stewart_param_info *info = stewart_param(i);
        targets.push_back({info->name, info->count, stewart_param_fills_from_scalar(i) != 0, i,
                           stewart_param_element(&params, i, 0),
                           std::vector<int>(static_cast<size_t>(info->count), -1)});
    }
    for (double *values : {neutral, travel})
        targets.push_back({values == neutral ? "stroke_neutral" : "stroke_travel", STEWART_LEGS,
                           true, -1, values, std::vector<int>(STEWART_LEGS, -1)});
    return targets;
}

// The fields put into params; false with the field that failed and why.
bool apply_fields(const std::vector<JsonField> &fields, stewart_params &params,
                  std::vector<unsigned char> &given, Problem &p) {
    double neutral[STEWART_LEGS] = {0}, travel[STEWART_LEGS] = {0};
    std::vector<Target> targets = make_targets(params, neutral, travel);
    stewart::FileUnits units;
    for (size_t i = 0; i < fields.size(); ++i)
        if (fields[i].name == "units" && !read_file_units(fields[i], units, p.why))
            return p.field = static_cast<int>(i), false;
    for (size_t i = 0; i < fields.size(); ++i) {
        const JsonField &f = fields[i];
        p.field = static_cast<int>(i);
        if (f.name == "units") continue;
        if (f.name == "description") {
            if (f.value.kind == JsonValue::Text) continue;
            return p.why = "description = " + shown(f) + " must be a string", false;
        }
        if (!apply(fields, static_cast<int>(i), targets, units, p.why)) return false;
    }
    auto target = [&](const char *name) -> Target & {
        return targets[static_cast<size_t>(stewart_param_find(name, nullptr))];
    };
    if (!strokes_from_travel(fields, targets, target("stroke_min[1]"), target("stroke_max[1]"),
                             p) ||
        !joints_complete(fields, target("geometry"), target("base_joint[1]"),
                         target("platform_joint[1]"), p))
        return false;
    for (const Target &t : targets)
        if (t.param >= 0) given[static_cast<size_t>(t.param)] = first_owner(t) >= 0;
    return true;
}

}  // namespace

extern "C" stewart_status stewart_params_read_json(stewart_params *params, const char *text,
                                                   size_t length, unsigned char *given, char *msg,
                                                   size_t size) {
    if (!params || !text) return set_message(msg, size, STEWART_ERR_ARGUMENT, "NULL argument");
    if (length > STEWART_PLATFORM_FILE_MAX_BYTES)
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "%zu bytes: a platform file has at most %d bytes", length,
                           STEWART_PLATFORM_FILE_MAX_BYTES);
    if (std::memchr(text, '\0', length))
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "a platform file is text: it holds a NUL byte");
    std::vector<JsonField> fields;
    std::string why;
    int line = 0, column = 0;
    if (!stewart::read_json_fields(text, length, "units", fields, why, line, column))
        return set_message(msg, size, STEWART_ERR_PARAMETER, "line %d column %d: %s", line, column,
                           why.c_str());
    stewart_params result = *params;  // params change only if every field is good
    std::vector<unsigned char> set(static_cast<size_t>(stewart_param_count()), 0);
    Problem p;
    if (!apply_fields(fields, result, set, p)) {
        const JsonField &f = fields[static_cast<size_t>(p.field)];
        return set_message(msg, size, STEWART_ERR_PARAMETER, "line %d column %d: %s", f.line,
                           f.column, p.why.c_str());
    }
    *params = result;
    if (given) std::memcpy(given, set.data(), set.size());
    return stewart::clear_message(msg, size);
}

namespace {

// What a path that is not a regular file is, for the message.
const char *file_kind(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

// The text of a regular file of at most the cap (one byte more says it is larger), or false
// with why. Opened without blocking: a FIFO with no writer is refused at once, not waited on.
bool read_regular_file(const char *path, std::string &text, std::string &why) {
    const int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return why = "cannot open the file: " + std::generic_category().message(errno), false;
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        why = std::string("is ") + file_kind(st.st_mode) + ": a platform file is a regular file";
        close(fd);
        return false;
    }
    const size_t cap = STEWART_PLATFORM_FILE_MAX_BYTES;
    text.resize(cap + 1);
    size_t n = 0;
    while (n < text.size()) {
        const ssize_t got = read(fd, &text[n], text.size() - n);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) {
            why = "cannot read the file: " + std::generic_category().message(errno);
            close(fd);
            return false;
        }
        if (got == 0) break;
        n += static_cast<size_t>(got);
    }
    close(fd);
    text.resize(n);
    if (n > cap)
        return why = "larger than " + std::to_string(cap) + " bytes: not a platform file", false;
    return true;
}

}  // namespace

extern "C" stewart_status stewart_params_read_json_file(stewart_params *params, const char *path,
                                                        unsigned char *given, char *msg,
                                                        size_t size) {
    if (!params || !path) return set_message(msg, size, STEWART_ERR_ARGUMENT, "NULL argument");
    std::string text, why;
    if (!read_regular_file(path, text, why))
        return set_message(msg, size, STEWART_ERR_PARAMETER, "%s", why.c_str());
    return stewart_params_read_json(params, text.data(), text.size(), given, msg, size);
}

namespace {

// One unit of a kind for the file: "units" wins; else the values' own unit if they all use one.
struct UnitVotes {
    const stewart::Unit *stated = nullptr, *written = nullptr;
    bool mixed = false;
    void add(const stewart::Unit *u) {
        if (written && written != u) mixed = true;
        written = u;
    }
    const char *name() const {
        return stated ? stated->name : written && !mixed ? written->name : "";
    }
};

void copy_name(char (&to)[8], const char *name) {
    std::strncpy(to, name, sizeof to - 1);
    to[sizeof to - 1] = '\0';
}

}  // namespace

extern "C" stewart_status stewart_platform_file_units(const char *path, stewart_file_units *units,
                                                      char *msg, size_t size) {
    if (!path || !units) return set_message(msg, size, STEWART_ERR_ARGUMENT, "NULL argument");
    std::string text, why;
    std::vector<JsonField> fields;
    int line = 0, column = 0;
    if (!read_regular_file(path, text, why))
        return set_message(msg, size, STEWART_ERR_PARAMETER, "%s", why.c_str());
    if (!stewart::read_json_fields(text.data(), text.size(), "units", fields, why, line, column))
        return set_message(msg, size, STEWART_ERR_PARAMETER, "line %d column %d: %s", line, column,
                           why.c_str());
    UnitVotes length, angle;
    for (const JsonField &f : fields) {
        for (const auto &m : f.value.members) {  // "units": {"length": "mm", ...}
            const stewart::Unit *u = stewart::find_unit(m.second);
            if (u && f.name == "units") (std::strcmp(u->si, "m") ? angle : length).stated = u;
        }
        std::vector<JsonItem> items = f.value.items;
        if (f.value.kind == JsonValue::Text && f.name != "description")  // "12.5 mm" alone
            items.push_back({f.value.text, true});
        for (const JsonItem &x : items) {
            std::string number, name;
            if (!x.quoted || !stewart::split_quantity(x.text, number, name)) continue;
            const stewart::Unit *u = stewart::find_unit(name);
            if (u) (std::strcmp(u->si, "m") ? angle : length).add(u);
        }
    }
    copy_name(units->length, length.name());
    copy_name(units->angle, angle.name());
    return stewart::clear_message(msg, size);
}

extern "C" const char *stewart_unit_per_si(const char *name, double *per_si) {
    const stewart::Unit *u = name ? stewart::find_unit(name) : nullptr;
    if (!u) return nullptr;
    if (per_si) *per_si = u->per_si;
    return u->si;
}
