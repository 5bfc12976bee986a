// stewart._core's tables Python reads at import (results.py, the option keywords): the output
// columns and option tables of each direction, and the status names.
#include "_core.hpp"

namespace stewart_core {

namespace {

// An option table for Python: one dict per option (name, id, integer, unit, min, max,
// min_closed, max_closed, default, description).
nb::list option_table(int (*count)(), const stewart_option_info *(*option)(int)) {
    nb::list table;
    for (int i = 0; i < count(); ++i) {
        const stewart_option_info *o = option(i);
        nb::dict entry;
        entry["name"] = o->name;
        entry["id"] = o->id;
        entry["integer"] = o->is_integer != 0;
        entry["unit"] = o->unit;
        entry["min"] = o->min;
        entry["max"] = o->max;
        entry["min_closed"] = o->min_closed != 0;
        entry["max_closed"] = o->max_closed != 0;
        entry["default"] = o->default_value;
        entry["description"] = o->description;
        table.append(entry);
    }
    return table;
}

// One output column of a direction's table (stewart_outputs.h) as Python sees it: name, values per
// row, numpy dtype, unit, description. Python makes the result arrays from these, so a column
// added to a table reaches the result classes without a binding change.
using ColumnInfo = std::tuple<std::string, int, std::string, std::string, std::string>;
#define STEWART_COLUMN_INFO(name, member, count, type, unit, description) \
    ColumnInfo{#name, count, dtype_name<type>(), unit, description},
std::vector<ColumnInfo> inverse_columns() {
    return {STEWART_INVERSE_OUTPUT_TABLE(STEWART_COLUMN_INFO)};
}
std::vector<ColumnInfo> forward_columns() {
    return {STEWART_FORWARD_OUTPUT_TABLE(STEWART_COLUMN_INFO)};
}
std::vector<ColumnInfo> plant_columns() {
    return {STEWART_PLANT_OUTPUT_TABLE(STEWART_COLUMN_INFO)
                STEWART_PLANT_STEP_TABLE(STEWART_COLUMN_INFO)};
}
#undef STEWART_COLUMN_INFO

}  // namespace

void bind_tables(nb::module_ &m) {
    m.def("inverse_columns", &inverse_columns,
          "(name, values per row, dtype, unit, description) of each inverse output column");
    m.def("forward_columns", &forward_columns,
          "(name, values per row, dtype, unit, description) of each forward output column");
    m.def("plant_columns", &plant_columns,
          "(name, values per row, dtype, unit, description) of each plant output column");
    m.def(
        "option_table",
        [](const std::string &direction) {
            if (direction == "inverse")
                return option_table(stewart_inverse_option_count, stewart_inverse_option);
            if (direction == "forward")
                return option_table(stewart_forward_option_count, stewart_forward_option);
            if (direction == "plant")
                return option_table(stewart_plant_option_count, stewart_plant_option);
            if (direction == "cueing")
                return option_table(stewart_cueing_option_count, stewart_cueing_option);
            fail(
                ("no option table '" + direction + "': inverse, forward, plant or cueing").c_str());
        },
        nb::arg("direction"),
        "The library's option table of a direction (inverse, forward, plant, cueing): one dict per "
        "option (name, id, integer, unit, min, max, min_closed, max_closed, default, "
        "description)");
    nb::class_<Placement>(m, "Placement",
                          "Where a result's arrays lie in its block (made by inverse_placement, "
                          "forward_placement)")
        .def_prop_ro("rows", &Placement::rows);
    m.def("status_name",
          [](int s) { return std::string(stewart_status_name(static_cast<stewart_status>(s))); });
    m.attr("BATCH_NOT_RUN") = STEWART_BATCH_NOT_RUN;
}

}  // namespace stewart_core
