// stewart-simulate: actuator forces CSV in, the platform's motion out (forward dynamics).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "cli/arguments.hpp"
#include "kinematics/pose_names.hpp"
#include "cli/param_assignment.hpp"
#include "cli/view_page.hpp"
#include "stewart/stewart_limits.h"
#include "stewart/stewart_plant.h"
#include "stewart/stewart_table.h"
#include "util/number_text.hpp"
#include "util/range.hpp"

namespace {

using stewart::kPoseNames;

int usage(FILE *to) {
    std::fprintf(to, "usage: stewart-simulate [--fidelity massless|full] [--platform FILE.json] "
                     "[--param NAME=VALUE ...] [--view[=PAGE.html]] IN.csv OUT.csv\n"
                     "  --platform: a platform file (docs/geometry.md: parameter names to values); "
                     "files and\n"
                     "           --param apply in the order given\n"
                     "  --param: a platform parameter by its FMU name (e.g. payload_mass=50), the "
                     "start\n"
                     "           state x0 y0 z0 roll0 pitch0 yaw0, x_dot0 .. yaw_dot0 (default: at "
                     "rest at home),\n"
                     "           or a plant option (the library's table; default in brackets):\n");
    for (int i = 0; i < stewart_plant_option_count(); ++i) {
        const stewart_option_info *o = stewart_plant_option(i);
        std::fprintf(to, "             %s [%s]: %s\n", o->name,
                     stewart::ExactText(o->default_value).c_str(), o->description);
    }
    std::fprintf(to,
                 "  IN.csv:  t,F1..F6 [s, N] (F_k > 0 pushes platform and base apart; linear in "
                 "time between rows)\n"
                 "  OUT.csv: t,x,y,z,roll,pitch,yaw,x_dot..yaw_dot,L1..L6,L_dot1..L_dot6,"
                 "warnings (bits: 1\n"
                 "           stroke, 8 joint angle, 16 leg interference),\n"
                 "           steps,rhs_evaluations,nonlinear_iterations,error_test_failures "
                 "(of the step into that row);\n"
                 "           with input 1 (F1..F6 are currents [A]) or 2 (voltages [V]) also "
                 "force1..6, current1..6,\n"
                 "           voltage1..6, motor_speed1..6, motor_torque1..6, "
                 "electrical_power1..6 and the bit sets\n"
                 "           current_max_legs, voltage_max_legs, motor_speed_max_legs\n"
                 "  A row that cannot be simulated stops the run: OUT.csv then holds the rows "
                 "before it\n"
                 "  (partial output), stderr names the row and why, and the exit status is 1.\n"
                 "  --view: and OUT.html (or PAGE.html), the rows written in 3D in a browser,\n"
                 "           self-contained, with the forces of IN.csv (docs/view.md)\n");
    return to == stderr ? 2 : 0;
}

struct Settings {
    stewart_params params;
    stewart_plant_options options;
    double pose[6], rate[6];
};

// NAME=VALUE into the settings; false with a message on stderr.
bool set_param(const char *assignment, Settings &s) {
    std::string name;
    double value;
    if (!stewart::parse_assignment("stewart-simulate", assignment, name, value)) return false;
    for (int i = 0; i < 6; ++i) {
        if (name == std::string(kPoseNames[i]) + "0") return s.pose[i] = value, true;
        if (name == std::string(kPoseNames[i]) + "_dot0") return s.rate[i] = value, true;
    }
    const int option = stewart_plant_option_find(name.c_str());
    if (option >= 0) {
        char message[STEWART_MESSAGE_SIZE];
        if (stewart_plant_option_set(&s.options, option, value, message, sizeof message) ==
            STEWART_OK)
            return true;
        std::fprintf(stderr, "stewart-simulate: --param %s\n", message);
        return false;
    }
    return stewart::set_platform_param("stewart-simulate", name, value, s.params);
}

std::vector<std::string> split(const std::string &line) {
    std::vector<std::string> out;
    size_t start = 0;
    for (;;) {
        const size_t comma = line.find(',', start);
        std::string cell =
            line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        const size_t b = cell.find_first_not_of(" \t\r"), e = cell.find_last_not_of(" \t\r");
        out.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
        if (comma == std::string::npos) return out;
        start = comma + 1;
    }
}

std::string number_text(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", v);
    return text;
}

struct ForceTable {
    std::vector<double> t;
    std::vector<double> force;  // 6 per row
};

// Reads t,F1..F6 (any column order, no other columns); "" or a message naming line and column.
std::string read_forces(const char *path, ForceTable &table) {
    std::ifstream in(path);
    if (!in) return std::string("cannot open ") + path;
    std::string line;
    if (!std::getline(in, line))
        return std::string(path) + " is empty: expected the header t,F1,F2,F3,F4,F5,F6";
    const std::vector<std::string> header = split(line);
    int column_of[7];  // t, F1..F6 -> column index
    const char *names[7] = {"t", "F1", "F2", "F3", "F4", "F5", "F6"};
    for (int c = 0; c < 7; ++c) {
        column_of[c] = -1;
        for (size_t i = 0; i < header.size(); ++i)
            if (header[i] == names[c]) column_of[c] = static_cast<int>(i);
        if (column_of[c] < 0)
            return std::string(path) + " line 1: column '" + names[c] +
                   "' is missing (expected t,F1,F2,F3,F4,F5,F6)";
    }
    if (header.size() != 7)
        return std::string(path) + " line 1: " + std::to_string(header.size()) +
               " columns; expected exactly t,F1,F2,F3,F4,F5,F6";
    int number = 1;
    while (std::getline(in, line)) {
        ++number;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        const std::vector<std::string> cells = split(line);
        const std::string where = std::string(path) + " line " + std::to_string(number);
        if (cells.size() != 7)
            return where + ": " + std::to_string(cells.size()) + " values, expected 7";
        double row[7];
        for (int c = 0; c < 7; ++c) {
            const std::string &cell = cells[column_of[c]];
            if (!stewart::read_double(cell, row[c]) || !std::isfinite(row[c]))
                return where + ", column " + std::to_string(column_of[c] + 1) + " (" + names[c] +
                       "): '" + cell + "' is not a finite number";
        }
        if (!table.t.empty() && !(row[0] > table.t.back()))
            return where + ", column " + std::to_string(column_of[0] + 1) +
                   " (t): t = " + number_text(row[0]) + " does not increase";
        table.t.push_back(row[0]);
        for (int k = 1; k <= 6; ++k) table.force.push_back(row[k]);
    }
    if (table.t.empty()) return std::string(path) + ": no data rows";
    return "";
}

// The warning for the first leg outside its stroke.
std::string stroke_warning(const stewart_params &p, const stewart_plant_output &o) {
    char text[STEWART_MESSAGE_SIZE] = "";
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (o.stroke_legs & (1 << k)) {
            std::snprintf(text, sizeof text,
                          "leg %d has left its stroke: length %.9g m outside [%g, %g] m (end "
                          "stops are not modelled)",
                          k + 1, o.lengths.length[k], p.stroke_min[k], p.stroke_max[k]);
            break;
        }
    return text;
}

struct Row {
    stewart_plant_output out;
    stewart_plant_statistics stats;
};

// The drives' columns (input current or voltage only: force input writes today's columns).
const char *const kDriveColumns[] = {"force",       "current",      "voltage",
                                     "motor_speed", "motor_torque", "electrical_power"};

void write_header(FILE *f, bool drives) {
    std::fprintf(f, "t");
    for (const char *p : kPoseNames) std::fprintf(f, ",%s", p);
    for (const char *p : kPoseNames) std::fprintf(f, ",%s_dot", p);
    for (int k = 1; k <= 6; ++k) std::fprintf(f, ",L%d", k);
    for (int k = 1; k <= 6; ++k) std::fprintf(f, ",L_dot%d", k);
    std::fprintf(f, ",warnings,steps,rhs_evaluations,nonlinear_iterations,error_test_failures");
    if (drives) {
        for (const char *c : kDriveColumns)
            for (int k = 1; k <= 6; ++k) std::fprintf(f, ",%s%d", c, k);
        std::fprintf(f, ",current_max_legs,voltage_max_legs,motor_speed_max_legs");
    }
    std::fprintf(f, "\n");
}

void write_row(FILE *f, const Row &r, bool drives) {
    const stewart_plant_output &o = r.out;
    std::fprintf(f, "%.17g", o.time);
    for (double v : o.pose.q) std::fprintf(f, ",%.17g", v);
    for (double v : o.pose.q_dot) std::fprintf(f, ",%.17g", v);
    for (double v : o.lengths.length) std::fprintf(f, ",%.17g", v);
    for (double v : o.lengths.length_rate) std::fprintf(f, ",%.17g", v);
    std::fprintf(f, ",%d,%ld,%ld,%ld,%ld", o.warnings, r.stats.steps, r.stats.rhs_evaluations,
                 r.stats.nonlinear_iterations, r.stats.error_test_failures);
    if (drives) {
        for (const double *column :
             {o.force, o.current, o.voltage, o.motor_speed, o.motor_torque, o.electrical_power})
            for (int k = 0; k < 6; ++k) std::fprintf(f, ",%.17g", column[k]);
        std::fprintf(f, ",%d,%d,%d", o.current_max_legs, o.voltage_max_legs,
                     o.motor_speed_max_legs);
    }
    std::fprintf(f, "\n");
}

// The warnings that start at row j (strokes, joint angles, interference: docs/limits.md), each
// when it starts.
void report_warnings(const stewart_params &params, size_t j, double t,
                     const stewart_plant_output &o, int &last_warnings) {
    const int started = o.warnings & ~last_warnings;
    const std::string why[] = {stroke_warning(params, o),
                               "a joint is beyond its angle limit (base_joint_limit, "
                               "platform_joint_limit; joint stops are not modelled)",
                               "two legs are closer than leg_diameter (contacts are not "
                               "modelled)"};
    const int bits[] = {STEWART_WARN_STROKE, STEWART_WARN_JOINT_LIMIT, STEWART_WARN_INTERFERENCE};
    for (int w = 0; w < 3; ++w)
        if (started & bits[w])
            std::fprintf(stderr, "stewart-simulate: warning at row %zu (t = %g): %s\n", j + 1, t,
                         why[w].c_str());
    last_warnings = o.warnings;
}

// Simulates the table's rows into rows from the start state (pose, rate): the number of rows
// computed, all of them unless one fails (its number and why on stderr).
size_t simulate_rows(stewart_plant *plant, const ForceTable &table, const stewart_params &params,
                     const double pose[6], const double rate[6], std::vector<Row> &rows) {
    if (stewart_plant_set_state(plant, table.t[0], pose, rate) != STEWART_OK) {
        std::fprintf(stderr, "stewart-simulate: start state: %s\n", stewart_plant_message(plant));
        return 0;
    }
    int last_warnings = 0;
    stewart_plant_input in{};
    for (size_t j = 0; j < table.t.size(); ++j) {
        const double *force = &table.force[6 * j];
        if (j > 0) {
            in.h = table.t[j] - table.t[j - 1];
            std::memcpy(in.force_start, &table.force[6 * (j - 1)], sizeof in.force_start);
            std::memcpy(in.force_end, force, sizeof in.force_end);
            const stewart_status st = stewart_plant_step(plant, &in, &rows[j].out);
            if (st != STEWART_OK) {
                std::fprintf(stderr, "stewart-simulate: row %zu (t = %g): %s: %s\n", j + 1,
                             table.t[j], stewart_status_name(st), stewart_plant_message(plant));
                return j;
            }
            stewart_plant_statistics_get(plant, &rows[j].stats);
        } else if (stewart_plant_output_get(plant, force, &rows[j].out) != STEWART_OK) {
            std::fprintf(stderr, "stewart-simulate: row %zu (t = %g): no outputs at this pose\n",
                         j + 1, table.t[j]);
            return 0;
        }
        report_warnings(params, j, table.t[j], rows[j].out, last_warnings);
    }
    return table.t.size();
}

// --view: the page of the first n rows (the plant's poses; the forces IN.csv gives, or with
// current or voltage input the plant's leg forces); 0, or 1 (said).
int write_view(const std::string &page, const char *out_csv, const stewart_params &params,
               const ForceTable &table, bool forces_given, const std::vector<Row> &rows, size_t n) {
    std::vector<double> t, q, force;
    if (forces_given) force.assign(table.force.begin(), table.force.begin() + 6 * n);
    for (size_t j = 0; j < n; ++j) {  // the rows' own times and poses, as OUT.csv's
        t.push_back(rows[j].out.time);
        q.insert(q.end(), rows[j].out.pose.q, rows[j].out.pose.q + 6);
        if (!forces_given) force.insert(force.end(), rows[j].out.force, rows[j].out.force + 6);
    }
    stewart_limits_options limits;  // the limit check's defaults, as stewart.view's
    stewart_limits_options_default(&limits);
    return stewart::write_view("stewart-simulate", page, out_csv, params, limits.warn_condition,
                               {t, q, force});
}

// Writes the header and the first n rows to path; false (said on stderr) if it cannot.
bool write_rows(const char *path, const std::vector<Row> &rows, size_t n, bool drives) {
    FILE *out = std::fopen(path, "w");
    if (!out) {
        std::fprintf(stderr, "stewart-simulate: cannot write %s\n", path);
        return false;
    }
    write_header(out, drives);
    for (size_t j = 0; j < n; ++j) write_row(out, rows[j], drives);
    if (std::fclose(out) != 0) {
        std::fprintf(stderr, "stewart-simulate: error writing %s\n", path);
        return false;
    }
    return true;
}

}  // namespace

int main(int argc, char **argv) {
    Settings s;
    stewart_params_default(&s.params);
    stewart_plant_options_default(&s.options);
    for (int i = 0; i < 6; ++i) s.pose[i] = s.rate[i] = 0;
    bool pose_z_given = false, view = false;
    std::string view_path;
    const char *paths[2] = {nullptr, nullptr};
    const std::vector<stewart::CliOption> cli = {
        {"--param", "NAME=VALUE",
         [&](const char *v) {
             if (!set_param(v, s)) return 2;
             if (!std::strncmp(v, "z0=", 3)) pose_z_given = true;
             return 0;
         }},
        {"--platform", "FILE.json",
         [&](const char *v) {
             return stewart::read_platform_file("stewart-simulate", v, s.params) ? 0 : 2;
         }},
        stewart::view_option("stewart-simulate", view, view_path),
        {"--fidelity", "massless|full",
         [&](const char *v) {
             if (!std::strcmp(v, "massless")) return s.options.fidelity = STEWART_MASSLESS, 0;
             if (!std::strcmp(v, "full")) return s.options.fidelity = STEWART_FULL, 0;
             std::fprintf(stderr, "stewart-simulate: unknown fidelity '%s'\n", v);
             return usage(stderr);
         }},
    };
    const int code =
        stewart::parse_command_line("stewart-simulate", argc, argv, cli, paths, 2, usage);
    if (code >= 0) return code;
    if (!pose_z_given) s.pose[2] = s.params.home_height;  // at home unless told otherwise
    if (view && *stewart::view_page_missing()) {
        std::fprintf(stderr, "stewart-simulate: --view: %s\n", stewart::view_page_missing());
        return 2;
    }

    char message[STEWART_MESSAGE_SIZE];
    if (stewart_plant_options_check(&s.options, message, sizeof message) != STEWART_OK) {
        std::fprintf(stderr, "stewart-simulate: %s\n", message);
        return 2;
    }
    ForceTable table;
    const std::string read_error = read_forces(paths[0], table);
    if (!read_error.empty()) {
        std::fprintf(stderr, "stewart-simulate: %s\n", read_error.c_str());
        return 1;
    }
    stewart_model *model = stewart_model_create(&s.params, message, sizeof message);
    stewart_plant *plant =
        model ? stewart_plant_create(model, &s.options, message, sizeof message) : nullptr;
    if (!plant) {
        std::fprintf(stderr, "stewart-simulate: cannot build the plant: %s\n", message);
        stewart_model_free(model);
        return 1;
    }
    std::vector<Row> rows(table.t.size());
    const size_t computed = simulate_rows(plant, table, s.params, s.pose, s.rate, rows);
    stewart_plant_free(plant);
    stewart_model_free(model);
    if (computed == 0) return 1;  // nothing to write: OUT.csv is left as it was
    if (!write_rows(paths[1], rows, computed, s.options.input != STEWART_PLANT_INPUT_FORCE))
        return 1;
    const bool forces_given = s.options.input == STEWART_PLANT_INPUT_FORCE;
    if (view && write_view(view_path, paths[1], s.params, table, forces_given, rows, computed) != 0)
        return 1;
    if (computed < rows.size()) {
        std::fprintf(stderr,
                     "stewart-simulate: %s holds the %zu rows before row %zu only (partial "
                     "output)\n",
                     paths[1], computed, computed + 1);
        return 1;
    }
    return 0;
}
