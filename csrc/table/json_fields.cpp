#include "table/json_fields.hpp"

#include <cmath>
#include <cstring>
#include <unordered_set>

#include "table/units.hpp"
#include "util/number_text.hpp"

namespace stewart {

namespace {

// The length of the well-formed UTF-8 sequence at `at` (a lead byte >= 0x80), or 0: no overlong
// forms, no surrogates, nothing above U+10FFFF (RFC 3629).
size_t utf8_length(const unsigned char *at, const unsigned char *end) {
    const unsigned char c = at[0];
    const size_t n = c >= 0xC2 && c <= 0xDF   ? 2
                     : c >= 0xE0 && c <= 0xEF ? 3
                     : c >= 0xF0 && c <= 0xF4 ? 4
                                              : 0;
    if (n == 0 || static_cast<size_t>(end - at) < n) return 0;
    for (size_t i = 1; i < n; ++i)
        if ((at[i] & 0xC0) != 0x80) return 0;
    if ((c == 0xE0 && at[1] < 0xA0) || (c == 0xED && at[1] > 0x9F) || (c == 0xF0 && at[1] < 0x90) ||
        (c == 0xF4 && at[1] > 0x8F))
        return 0;
    return n;
}

// A recursive-descent reader of exactly the subset; error() keeps the first problem and where.
class Reader {
public:
    Reader(const char *text, size_t length, const char *object_field)
        : end_(text + length), at_(text), line_start_(text), object_field_(object_field) {}

    bool object(std::vector<JsonField> &fields) {
        std::unordered_set<std::string> names;  // a hash set: linear in the number of fields
        if (end_ - at_ >= 3 && !std::memcmp(at_, "\xEF\xBB\xBF", 3))
            at_ += 3, line_start_ = at_;  // an editor's BOM
        space();
        if (!take('{')) return error("a platform file is one JSON object: expected '{'");
        space();
        if (take('}')) return finish();
        for (;;) {
            JsonField f;
            space();
            f.line = line_, f.column = column();
            if (!string(f.name)) return false;
            space();
            if (!take(':')) return error("expected ':' after \"" + f.name + "\"");
            space();
            if (!value(f.name, f.value)) return false;
            if (!names.insert(f.name).second) {
                at_line_ = f.line, at_column_ = f.column;
                return error("\"" + f.name + "\" is given twice");
            }
            fields.push_back(std::move(f));
            space();
            if (take('}')) return finish();
            if (!take(','))
                return error("expected ',' or '}' after the value of \"" + fields.back().name +
                             "\"");
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

    // A string without control characters; the escapes \" \\ \/ only (names, units and
    // descriptions need no others).
    bool string(std::string &out) {
        if (!take('"')) return error("expected a name in double quotes");
        out.clear();
        while (at_ < end_ && *at_ != '"') {
            const unsigned char c = static_cast<unsigned char>(*at_);
            if (c < 0x20) return error("a control character inside a string");
            if (c >= 0x80) {  // a UTF-8 sequence, copied whole
                const size_t n = utf8_length(reinterpret_cast<const unsigned char *>(at_),
                                             reinterpret_cast<const unsigned char *>(end_));
                if (n == 0)
                    return error(
                        "a platform file is UTF-8: a byte that is not UTF-8 inside a string");
                out.append(at_, n);
                at_ += n;
                continue;
            }
            if (c == '\\') {
                ++at_;
                if (at_ == end_ || (*at_ != '"' && *at_ != '\\' && *at_ != '/'))
                    return error("only the escapes \\\" \\\\ \\/ are read in a platform file");
            }
            out.push_back(*at_++);
        }
        return take('"') || error("a string without its closing '\"'");
    }

    // A JSON number, finite as a double.
    bool number(const std::string &field, JsonItem &out) {
        const size_t n = json_number_length(std::string_view(at_, static_cast<size_t>(end_ - at_)));
        if (n == 0) {
            if (at_ < end_ && (*at_ == '-' || (*at_ >= '0' && *at_ <= '9')))
                return error(field + ": a number needs digits before and after '.' and after "
                                     "the exponent's 'e'");
            return error(field + ": expected a number (true, false, null, NaN and Infinity are "
                                 "not numbers)");
        }
        out.text.assign(at_, n);
        out.quoted = false;
        at_ += n;
        double value = 0;
        if (!read_double(out.text, value) || !std::isfinite(value))
            return error(field + " = " + out.text + " is not a finite double");
        return true;
    }

    // A number, or a string holding one with its unit.
    bool item(const std::string &field, JsonItem &out) {
        if (at_ < end_ && *at_ == '"') return out.quoted = true, string(out.text);
        return number(field, out);
    }

    bool members(const std::string &field, JsonValue &v) {
        v.kind = JsonValue::Object;
        space();
        if (take('}')) return true;
        for (;;) {
            std::pair<std::string, std::string> m;
            space();
            if (!string(m.first)) return false;
            space();
            if (!take(':')) return error("expected ':' after \"" + m.first + "\" in " + field);
            space();
            if (at_ == end_ || *at_ != '"')
                return error(field + "." + m.first + ": expected a string");
            if (!string(m.second)) return false;
            for (const auto &seen : v.members)  // a handful of members
                if (seen.first == m.first) return error(field + "." + m.first + " is given twice");
            v.members.push_back(m);
            space();
            if (take('}')) return true;
            if (!take(',')) return error(field + ": expected ',' or '}' in the object");
        }
    }

    bool value(const std::string &field, JsonValue &v) {
        if (at_ < end_ && *at_ == '"') return v.kind = JsonValue::Text, string(v.text);
        if (take('[')) {
            v.kind = JsonValue::List;
            space();
            if (take(']')) return true;
            for (;;) {
                space();
                if (at_ < end_ && (*at_ == '[' || *at_ == '{'))
                    return error(field + ": a list holds numbers only");
                JsonItem x;
                if (!item(field + "[" + std::to_string(v.items.size() + 1) + "]", x)) return false;
                v.items.push_back(std::move(x));
                space();
                if (take(']')) return true;
                if (!take(',')) return error(field + ": expected ',' or ']' in the list");
            }
        }
        if (take('{')) {
            if (field == object_field_) return members(field, v);
            --at_;
            return error(field + ": objects are not values here");
        }
        v.kind = JsonValue::Number;
        v.items.resize(1);
        return number(field, v.items[0]);
    }

    const char *end_, *at_;
    const char *line_start_;
    int line_ = 1;
    int at_line_ = 0, at_column_ = 0;
    std::string message_;
    std::string object_field_;
};

}  // namespace

bool read_json_fields(const char *text, size_t length, const char *object_field,
                      std::vector<JsonField> &fields, std::string &message, int &line,
                      int &column) {
    Reader reader(text, length, object_field);
    const bool ok = reader.object(fields);
    if (!ok) message = reader.message(), line = reader.line(), column = reader.column_of_error();
    return ok;
}

}  // namespace stewart
