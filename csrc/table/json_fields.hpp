// The JSON subset platform files are written in: one object of names to numbers, strings ("12.5
// mm"), lists of those, or (for "units" only) an object of names to strings. Read in one pass,
// in time linear in the text.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace stewart {

// One number as the file wrote it: a JSON number, or a string (quoted: "12.5 mm").
struct JsonItem {
    std::string text;
    bool quoted = false;
};

struct JsonValue {
    enum Kind { Number, List, Text, Object } kind = Number;
    std::vector<JsonItem> items;                               // Number: one; List: each
    std::string text;                                          // Text
    std::vector<std::pair<std::string, std::string>> members;  // Object
};

struct JsonField {
    std::string name;
    JsonValue value;
    int line = 1, column = 1;  // where the name starts
};

// The fields of text (length bytes) in file order, or false with the first problem in message
// and where it is in line, column. A name given twice (spelt the same) is a problem; an object
// is read only as the value of a field named object_field.
bool read_json_fields(const char *text, size_t length, const char *object_field,
                      std::vector<JsonField> &fields, std::string &message, int &line, int &column);

}  // namespace stewart
