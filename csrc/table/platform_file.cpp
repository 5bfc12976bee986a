// Platform files (stewart/stewart_platform_file.h): a strict reader of the JSON subset they use
// (one object of names to numbers, lists of numbers, or the description's string), each field
// checked against the parameter table before any is set.
#include "stewart/stewart_platform_file.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "stewart/stewart_table.h"
#include "util/message.hpp"
#include "util/range.hpp"

using stewart::set_message;

namespace {

// One value of the subset.
struct Value {
    enum Kind { Number, List, Text } kind = Number;
    double number = 0;
    std::vector<double> list;
    std::string text;
};

struct Field {
    std::string name;
    Value value;
    int line = 1, column = 1;  // where the name starts
};

// A recursive-descent reader of exactly the subset; error() keeps the first problem and where.
class Reader {
  public:
    Reader(const char *text, size_t length) : text_(text), end_(text + length), at_(text) {}

    bool object(std::vector<Field> &fields) {
        space();
        if (!take('{')) return error("a platform file is one JSON object: expected '{'");
        space();
        if (take('}')) return finish();
        for (;;) {
            Field f;
            space();
            f.line = line_, f.column = column();
            if (!string(f.name)) return false;
            space();
            if (!take(':')) return error("expected ':' after \"" + f.name + "\"");
            space();
            if (!value(f.name, f.value)) return false;
            for (const Field &seen : fields)
                if (seen.name == f.name) {
                    at_line_ = f.line, at_column_ = f.column;
                    return error("\"" + f.name + "\" is given twice");
                }
            fields.push_back(f);
            space();
            if (take('}')) return finish();
            if (!take(',')) return error("expected ',' or '}' after the value of \"" + f.name + "\"");
        }
    }

    const std::string &message() const { return message_; }
    int line() const { return at_line_; }
    int column_of_error() const { return at_column_; }

  private:
    bool finish() {
        space();
        return at_ == end_ || error("unexpected text after the object's closing '}'");
    }

    bool error(const std::string &what) {
        if (message_.empty()) {
            message_ = what;
            if (at_line_ == 0) at_line_ = line_, at_column_ = column();
        }
        return false;
    }

    int column() const { return static_cast<int>(at_ - line_start_) + 1; }

    void space() {
        while (at_ < end_ && (*at_ == ' ' || *at_ == '\t' || *at_ == '\r' || *at_ == '\n')) {
            if (*at_ == '\n') ++line_, line_start_ = at_ + 1;
            ++at_;
        }
    }

    bool take(char c) {
        if (at_ < end_ && *at_ == c) return ++at_, true;
        return false;
    }

    // A string without control characters; the escapes \" \\ \/ only (names and descriptions
    // need no others).
    bool string(std::string &out) {
        if (!take('"')) return error("expected a name in double quotes");
        out.clear();
        while (at_ < end_ && *at_ != '"') {
            const unsigned char c = static_cast<unsigned char>(*at_);
            if (c < 0x20) return error("a control character inside a string");
            if (c == '\\') {
                ++at_;
                if (at_ == end_ || (*at_ != '"' && *at_ != '\\' && *at_ != '/'))
                    return error("only the escapes \\\" \\\\ \\/ are read in a platform file");
            }
            out.push_back(*at_++);
        }
        return take('"') || error("a string without its closing '\"'");
    }

    // A JSON number: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?, finite as a double.
    bool number(const std::string &field, double &out) {
        const char *start = at_;
        auto digits = [&] {
            const char *from = at_;
            while (at_ < end_ && *at_ >= '0' && *at_ <= '9') ++at_;
            return at_ > from;
        };
        take('-');
        if (take('0')) {
        } else if (!digits()) {
            at_ = start;
            return error(field + ": expected a number (true, false, null, NaN and Infinity are "
                                 "not numbers)");
        }
        if (take('.') && !digits()) return error(field + ": a digit must follow '.'");
        if (at_ < end_ && (*at_ == 'e' || *at_ == 'E')) {
            ++at_;
            if (!take('+')) take('-');
            if (!digits()) return error(field + ": a digit must follow the exponent's 'e'");
        }
        const std::string literal(start, at_);
        out = std::strtod(literal.c_str(), nullptr);
        if (!std::isfinite(out)) return error(field + " = " + literal + " is not a finite double");
        return true;
    }

    bool value(const std::string &field, Value &v) {
        if (at_ < end_ && *at_ == '"') return v.kind = Value::Text, string(v.text);
        if (take('[')) {
            v.kind = Value::List;
            space();
            if (take(']')) return true;
            for (;;) {
                space();
                double x = 0;
                if (at_ < end_ && (*at_ == '[' || *at_ == '{' || *at_ == '"'))
                    return error(field + ": a list holds numbers only");
                if (!number(field + "[" + std::to_string(v.list.size() + 1) + "]", x)) return false;
                v.list.push_back(x);
                space();
                if (take(']')) return true;
                if (!take(',')) return error(field + ": expected ',' or ']' in the list");
            }
        }
        if (at_ < end_ && *at_ == '{') return error(field + ": objects are not values here");
        v.kind = Value::Number;
        return number(field, v.number);
    }

    const char *text_, *end_, *at_;
    const char *line_start_ = text_;
    int line_ = 1;
    int at_line_ = 0, at_column_ = 0;
    std::string message_;
};

// "name = [1, 2, 3]" or "name = 0.5": a value as the file gave it, for messages.
std::string shown(const Field &f) {
    if (f.value.kind == Value::Text) return "\"" + f.value.text + "\"";
    if (f.value.kind == Value::Number) return stewart::ExactText(f.value.number).c_str();
    std::string s = "[";
    for (size_t i = 0; i < f.value.list.size(); ++i)
        s += (i ? ", " : "") + std::string(stewart::ExactText(f.value.list[i]).c_str());
    return s + "]";
}

// Puts field f into params (checked against the table); false with the message in why.
bool apply(const Field &f, stewart_params &params, std::vector<unsigned char> &given,
           std::string &why) {
    char message[STEWART_MESSAGE_SIZE];
    int element = 0, i = -1;
    for (int k = 0; k < stewart_param_count(); ++k)  // the whole parameter by its own name
        if (f.name == stewart_param(k)->name) i = k;
    const bool whole = i >= 0;
    if (!whole && (i = stewart_param_find(f.name.c_str(), &element)) < 0) {
        stewart_params scratch = params;  // not in the table: the library names the nearest
        stewart_params_set(&scratch, f.name.c_str(), 0.0, message, sizeof message);
        return why = message, false;
    }
    const stewart_param_info *info = stewart_param(i);
    std::vector<double> values;
    if (f.value.kind == Value::Text)
        return why = f.name + " = " + shown(f) + " must be a number" +
                     (whole && info->count > 1 ? " or a list of numbers" : ""), false;
    if (f.value.kind == Value::List) {
        if (!whole || info->count == 1)
            return why = f.name + " = " + shown(f) + " must be one number", false;
        if (static_cast<int>(f.value.list.size()) != info->count)
            return why = f.name + " has " + std::to_string(f.value.list.size()) +
                         " values: it needs " + std::to_string(info->count) + ", " + f.name +
                         "[1].." + f.name + "[" + std::to_string(info->count) + "]", false;
        values = f.value.list;
    } else if (whole && info->count > 1 && !stewart_param_fills_from_scalar(i)) {
        return why = f.name + " = " + shown(f) + " must be a list of its " +
                     std::to_string(info->count) + " values", false;
    } else {
        values.assign(whole ? info->count : 1, f.value.number);
    }
    for (size_t k = 0; k < values.size(); ++k) {
        const int e = whole ? static_cast<int>(k) : element;
        if (stewart_param_check_value(i, e, values[k], message, sizeof message) != STEWART_OK)
            return why = message, false;
        *stewart_param_element(&params, i, e) = values[k];
    }
    given[i] = 1;
    return true;
}

}  // namespace

extern "C" stewart_status stewart_params_read_json(stewart_params *params, const char *text,
                                                   size_t length, unsigned char *given,
                                                   char *msg, size_t size) {
    if (!params || !text) return set_message(msg, size, STEWART_ERR_ARGUMENT, "NULL argument");
    if (std::memchr(text, '\0', length))
        return set_message(msg, size, STEWART_ERR_PARAMETER, "a platform file is text: it holds a NUL byte");
    Reader reader(text, length);
    std::vector<Field> fields;
    if (!reader.object(fields))
        return set_message(msg, size, STEWART_ERR_PARAMETER, "line %d column %d: %s",
                           reader.line(), reader.column_of_error(), reader.message().c_str());
    stewart_params result = *params;  // params change only if every field is good
    std::vector<unsigned char> set(stewart_param_count(), 0);
    std::string why;
    for (const Field &f : fields) {
        if (f.name == "description") {
            if (f.value.kind == Value::Text) continue;
            why = "description = " + shown(f) + " must be a string";
        }
        if (why.empty() && apply(f, result, set, why)) continue;
        return set_message(msg, size, STEWART_ERR_PARAMETER, "line %d column %d: %s", f.line,
                           f.column, why.c_str());
    }
    // The joints are the geometry's only if geometry is 1, and then both sides come from the file.
    const int geometry = stewart_param_find("geometry", nullptr);
    const int sides[2] = {stewart_param_find("base_joint[1]", nullptr),
                          stewart_param_find("platform_joint[1]", nullptr)};
    const bool joints_given = set[sides[0]] || set[sides[1]];
    if (joints_given && !(set[geometry] && result.geometry == 1.0))
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "the file gives %s but not geometry = 1: the joints would be ignored "
                           "(geometry 0 places them on the circles)",
                           set[sides[0]] ? "base_joint" : "platform_joint");
    if (set[geometry] && result.geometry == 1.0)
        for (int side : sides)
            if (!set[side])
                return set_message(msg, size, STEWART_ERR_PARAMETER,
                                   "the file gives geometry = 1 but not %s: a platform file "
                                   "gives all its joints", stewart_param(side)->name);
    *params = result;
    if (given) std::memcpy(given, set.data(), set.size());
    return stewart::clear_message(msg, size);
}
