// stewart-solve: pose trajectory CSV in, actuator lengths, rates, accelerations and forces out.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "cli/arguments.hpp"
#include "cli/forward_table.hpp"
#include "cli/output_units.hpp"
#include "cli/param_assignment.hpp"
#include "cli/pose_table.hpp"
#include "cli/view_page.hpp"
#include "util/number_text.hpp"
#include "util/range.hpp"
#include "stewart/stewart.h"
#include "stewart/stewart_batch.h"
#include "stewart/stewart_check.h"
#include "stewart/stewart_limits.h"
#include "stewart/stewart_table.h"

namespace {

// A direction's option table (stewart_table.h), through its functions.
struct OptionTable {
    const char *direction;
    int (*find)(const char *name);
    int (*count)();
    const stewart_option_info *(*option)(int i);
};
const OptionTable kInverseOptions = {"the inverse solver", stewart_inverse_option_find,
                                     stewart_inverse_option_count, stewart_inverse_option};
const OptionTable kForwardOptions = {"forward kinematics", stewart_forward_option_find,
                                     stewart_forward_option_count, stewart_forward_option};

// A table's lines of the usage text: "NAME [DEFAULT]: DESCRIPTION".
void print_options(FILE *to, const OptionTable &table) {
    for (int i = 0; i < table.count(); ++i) {
        const stewart_option_info *o = table.option(i);
        std::fprintf(to, "             %s [%s]: %s\n", o->name,
                     stewart::ExactText(o->default_value).c_str(), o->description);
    }
}

int usage(FILE *to) {
    std::fprintf(to,
                 "usage: stewart-solve [--fidelity kinematic|massless|full] [--tolerance TOL] "
                 "[--platform FILE.json] [--param NAME=VALUE ...] [--static] [--limits] [--report] "
                 "[--ranges] [--units mm,deg] [--view[=PAGE.html]] IN.csv OUT.csv\n"
                 "  --platform: a platform file (docs/geometry.md: parameter names to values)\n"
                 "  --param: any platform parameter by its FMU name, SI units (e.g. "
                 "payload_mass=50,\n"
                 "           base_angle[2]=0.5236); the others are the thesis platform's; files "
                 "and --param\n"
                 "           apply in the order given; or an option of the inverse solver (the "
                 "library's table;\n"
                 "           default in brackets; --fidelity and --tolerance are two of them):\n");
    print_options(to, kInverseOptions);
    std::fprintf(
        to,
        "  IN.csv:  t,x,y,z,roll,pitch,yaw [m, rad], optionally x_dot..yaw_dot and "
        "x_ddot..yaw_ddot\n"
        "           (missing derivatives come from finite differences of the samples)\n"
        "  --static: the poses are at rest: missing derivatives are zero, not differences\n"
        "  OUT.csv: t,L1..L6,L_dot1..L_dot6,L_ddot1..L_ddot6,F1..F6,condition,iterations,\n"
        "           status (the first limit class the pose fails, none: within every limit)\n"
        "  --limits: and limit_class (the first failing: none, stroke, base_joint,\n"
        "           platform_joint, interference, condition) and the margin to each [m, rad,\n"
        "           rad, m, 1] (docs/limits.md); --report: as --limits with the leg classes\n"
        "           too (leg_speed, leg_accel from the rows' derivatives, leg_force from F)\n"
        "           [m/s, m/s^2, m/s^3, N]; --ranges: and each axis' range, the others\n"
        "           held: x_min,x_max, ..., yaw_max\n"
        "  --units: OUT.csv's lengths (m, cm, mm, um, nm, in) and angles (rad, deg, mrad,\n"
        "           urad), e.g.\n"
        "           mm,deg (default m,rad; forces, conditions, margin_axis and the drive columns\n"
        "           stay SI)\n"
        "  --view: and OUT.html (or PAGE.html), the run in 3D in a browser, self-contained\n"
        "           (docs/view.md)\n"
        "usage: stewart-solve --forward [--guess x,y,z,roll,pitch,yaw] [--tolerance TOL] "
        "[--platform FILE.json] [--param NAME=VALUE ...] [--units mm,deg] IN.csv OUT.csv\n"
        "  IN.csv:  t,L1..L6 [m], optionally L_dot1..L_dot6 and L_ddot1..L_ddot6 (other "
        "columns ignored)\n"
        "  OUT.csv: t,x,y,z,roll,pitch,yaw, x_dot.. and x_ddot.. when given their "
        "inputs, iterations,residual,condition\n"
        "  --guess: the first row's start (default: home); each later row tracks the "
        "one before\n"
        "  --cold: every row on its own from --guess or home (measured poses, not a "
        "trajectory)\n"
        "  --param: also an option of forward kinematics (the library's table; "
        "--tolerance is one):\n");
    print_options(to, kForwardOptions);
    std::fprintf(to,
                 "usage: stewart-solve --check FILE.json [--platform FILE.json] [--param "
                 "NAME=VALUE ...] [--units mm,deg]\n"
                 "  prints the home pose against every limit, the axis ranges and hints on entry "
                 "mistakes;\n"
                 "  exit status 1 when home is not a valid pose (docs/geometry.md); in FILE.json's "
                 "units (its\n"
                 "  \"units\", else the unit its values are written in; else m and deg), or "
                 "those --units names\n");
    return to == stderr ? 2 : 0;
}

bool parse_fidelity(const char *s, int &f) {
    if (!std::strcmp(s, "kinematic")) f = STEWART_KINEMATIC;
    else if (!std::strcmp(s, "massless")) f = STEWART_MASSLESS;
    else if (!std::strcmp(s, "full")) f = STEWART_FULL;
    else return false;
    return true;
}

const char *const kAxes[6] = {"x", "y", "z", "roll", "pitch", "yaw"};

// What a row reports beyond the solve: the limit check (its first class is the status column;
// --limits adds the margins) and, with --ranges, the axis ranges.
struct LimitRow {
    stewart_limits_output check;
    stewart_axis_ranges ranges;
};

// The classes --limits writes (the pose's own), and --report (every class, the legs' too).
int limit_columns(bool limits, bool report) {
    return report ? STEWART_LIMIT_CLASSES : limits ? STEWART_LIMIT_AXIS : 0;
}

// The drive columns (STEWART_INVERSE_DRIVE_OUTPUT_TABLE), only for a model with drives: a
// column of six as name1..name6, a bit set as its name.
void write_drive_header(FILE *out) {
#define DRIVE_HEADER(name, member, count, type, unit, description) \
    if ((count) == 1) std::fprintf(out, "," #name);                \
    else                                                           \
        for (int k = 1; k <= (count); ++k) std::fprintf(out, "," #name "%d", k);
    STEWART_INVERSE_DRIVE_OUTPUT_TABLE(DRIVE_HEADER)
#undef DRIVE_HEADER
}

void put_value(FILE *out, double value) { std::fprintf(out, ",%.17g", value); }
void put_value(FILE *out, int value) { std::fprintf(out, ",%d", value); }
template <typename T, size_t N>
void put_values(FILE *out, const T (&values)[N]) {
    for (const T &v : values) put_value(out, v);
}
void put_values(FILE *out, int value) { put_value(out, value); }

void write_drive_row(FILE *out, const stewart_inverse_output &o) {
#define DRIVE_ROW(name, member, count, type, unit, description) put_values(out, o.member);
    STEWART_INVERSE_DRIVE_OUTPUT_TABLE(DRIVE_ROW)
#undef DRIVE_ROW
}

void write_header(FILE *out, int limits, bool ranges, bool drives) {
    std::fprintf(out, "t");
    const char *groups[4] = {"L", "L_dot", "L_ddot", "F"};
    for (const char *g : groups)
        for (int k = 1; k <= STEWART_LEGS; ++k) std::fprintf(out, ",%s%d", g, k);
    std::fprintf(out, ",condition,iterations,status");
    if (limits) {
        std::fprintf(out, ",limit_class");
        for (int c = 1; c <= limits; ++c)
            std::fprintf(out, ",margin_%s", stewart_limit_class_name(c));
    }
    if (ranges)
        for (const char *axis : kAxes) std::fprintf(out, ",%s_min,%s_max", axis, axis);
    if (drives) write_drive_header(out);
    std::fprintf(out, "\n");
}

void write_row(FILE *out, double t, const stewart_inverse_output &o, const LimitRow &row,
               int limits, bool ranges, bool drives, const stewart::OutputUnits &u) {
    const stewart_limits_output &check = row.check;
    std::fprintf(out, "%.17g", t);
    const double *groups[4] = {o.lengths.length, o.lengths.length_rate, o.lengths.length_accel,
                               o.force};
    for (int g = 0; g < 4; ++g)
        for (int k = 0; k < STEWART_LEGS; ++k)
            std::fprintf(out, ",%.17g", g < 3 ? groups[g][k] * u.length : groups[g][k]);
    std::fprintf(out, ",%.17g,%d,%s", o.condition, o.iterations,
                 stewart_limit_class_name(check.first));
    if (limits) {
        std::fprintf(out, ",%s", stewart_limit_class_name(check.first));
        // stroke, joints, interference, condition, axis (its own axis' unit: kept SI), leg
        // speed, acceleration, jerk (lengths per time: the length unit), force (N)
        const double factor[STEWART_LIMIT_CLASSES] = {u.length, u.angle,  u.angle,  u.length, 1,
                                                      1,        u.length, u.length, u.length, 1};
        for (int c = 0; c < limits; ++c) std::fprintf(out, ",%.17g", check.margin[c] * factor[c]);
    }
    if (ranges)
        for (int a = 0; a < 6; ++a) {
            const double f = a < 3 ? u.length : u.angle;
            std::fprintf(out, ",%.17g,%.17g", row.ranges.min[a] * f, row.ranges.max[a] * f);
        }
    if (drives) write_drive_row(out, o);
    std::fprintf(out, "\n");
}

// What the command line asks for.
struct Request {
    stewart_inverse_options options;
    stewart_forward_options forward_options;
    std::vector<std::string> options_given;  // the option names --param set, in order
    stewart_params params;
    const char *paths[2] = {nullptr, nullptr};
    bool forward = false, cold = false, check = false, at_rest = false;
    bool limits = false, report = false, ranges = false, view = false;
    const char *check_path = nullptr;   // --check's file: the report is in its units
    const char *units_given = nullptr;  // --units' text
    std::string view_path;              // --view=PAGE.html; "": OUT.html
    stewart::OutputUnits units;
    double guess[6];
    const double *guess_given = nullptr;
};

// NAME=VALUE: an option of the inverse or the forward table (stewart_table.h; a name both have,
// as tolerance, is set in both: the run uses one of them), else a platform parameter; false with
// a message on stderr.
bool set_param(const char *assignment, Request &r) {
    std::string name;
    double value;
    if (!stewart::parse_assignment("stewart-solve", assignment, name, value)) return false;
    const int inverse = kInverseOptions.find(name.c_str());
    const int forward = kForwardOptions.find(name.c_str());
    if (inverse < 0 && forward < 0)
        return stewart::set_platform_param("stewart-solve", name, value, r.params);
    char message[STEWART_MESSAGE_SIZE];
    const bool set =
        (inverse < 0 || stewart_inverse_option_set(&r.options, inverse, value, message,
                                                   sizeof message) == STEWART_OK) &&
        (forward < 0 || stewart_forward_option_set(&r.forward_options, forward, value, message,
                                                   sizeof message) == STEWART_OK);
    if (!set) {
        std::fprintf(stderr, "stewart-solve: --param %s\n", message);
        return false;
    }
    r.options_given.push_back(name);
    return true;
}

// An option --param set that the direction run has not (its table lacks the name) would be
// ignored: refused instead, naming the direction's options. True when every one is the run's.
bool options_belong_to(const std::vector<std::string> &given, const OptionTable &table) {
    for (const std::string &name : given) {
        if (table.find(name.c_str()) >= 0) continue;
        std::string names;
        for (int i = 0; i < table.count(); ++i)
            names += (i ? ", " : "") + std::string(table.option(i)->name);
        std::fprintf(stderr, "stewart-solve: --param %s: not an option of %s (its options: %s)\n",
                     name.c_str(), table.direction, names.c_str());
        return false;
    }
    return true;
}

// Parses argv into request; -1 to go on, else the exit code.
int parse(int argc, char **argv, Request &r) {
    stewart_inverse_options_default(&r.options);
    stewart_forward_options_default(&r.forward_options);
    stewart_params_default(&r.params);
    const std::vector<stewart::CliOption> cli = {
        {"--forward", nullptr, [&](const char *) { return r.forward = true, 0; }},
        {"--cold", nullptr, [&](const char *) { return r.cold = true, 0; }},
        {"--static", nullptr, [&](const char *) { return r.at_rest = true, 0; }},
        {"--guess", "x,y,z,roll,pitch,yaw",
         [&](const char *v) {
             const std::vector<std::string> cells = stewart::csv_cells(v);
             bool read = cells.size() == 6;
             for (size_t i = 0; read && i < 6; ++i)
                 read = stewart::read_double(cells[i], r.guess[i]);
             if (!read) {
                 std::fprintf(stderr, "stewart-solve: --guess needs x,y,z,roll,pitch,yaw\n");
                 return 2;
             }
             return r.guess_given = r.guess, 0;
         }},
        {"--param", "NAME=VALUE", [&](const char *v) { return set_param(v, r) ? 0 : 2; }},
        {"--platform", "FILE.json",
         [&](const char *v) {
             return stewart::read_platform_file("stewart-solve", v, r.params) ? 0 : 2;
         }},
        {"--check", "FILE.json",
         [&](const char *v) {
             r.check = true;
             r.check_path = v;
             return stewart::read_platform_file("stewart-solve", v, r.params) ? 0 : 2;
         }},
        {"--limits", nullptr, [&](const char *) { return r.limits = true, 0; }},
        {"--report", nullptr, [&](const char *) { return r.report = true, 0; }},
        {"--ranges", nullptr, [&](const char *) { return r.ranges = true, 0; }},
        stewart::view_option("stewart-solve", r.view, r.view_path),
        {"--units", "mm,deg",
         [&](const char *v) {
             r.units_given = v;
             return stewart::parse_output_units("stewart-solve", v, r.units) ? 0 : 2;
         }},
        {"--fidelity", "kinematic|massless|full",
         [&](const char *v) {
             if (parse_fidelity(v, r.options.fidelity)) return 0;
             std::fprintf(stderr, "stewart-solve: unknown fidelity '%s'\n", v);
             return usage(stderr);
         }},
        {"--tolerance", "a positive number",  // checked with the other options, as given
         [&](const char *v) {
             if (stewart::read_double(v, r.options.tolerance))
                 return r.forward_options.tolerance = r.options.tolerance, 0;
             std::fprintf(stderr, "stewart-solve: --tolerance '%s' is not a number\n", v);
             return 2;
         }},
    };
    bool checking = false;
    for (int i = 1; i < argc; ++i) checking = checking || !std::strcmp(argv[i], "--check");
    return stewart::parse_command_line("stewart-solve", argc, argv, cli, r.paths, checking ? 0 : 2,
                                       usage);
}

// --check: the home pose's report on stdout; 1 when home is not valid.
int run_check(const Request &r) {
    char message[STEWART_MESSAGE_SIZE];
    stewart_model *model = stewart_model_create(&r.params, message, sizeof message);
    if (!model) {
        std::fprintf(stderr, "stewart-solve: cannot build the model: %s\n", message);
        return 1;
    }
    stewart_limits_options limit_options;
    stewart_limits_options_default(&limit_options);
    limit_options.warn_condition = r.options.warn_condition;
    stewart_check_report report;
    const stewart_status s =
        stewart_check_home(model, &limit_options, &report, message, sizeof message);
    stewart_model_free(model);
    if (s != STEWART_OK) {
        std::fprintf(stderr, "stewart-solve: --check: %s\n", message);
        return 1;
    }
    // The file's units, those --units names over them; m and deg where neither says.
    stewart::OutputUnits units;
    if (!stewart::parse_output_units("stewart-solve", "m,deg", units) ||
        !stewart::file_output_units("stewart-solve --check", r.check_path, units) ||
        (r.units_given && !stewart::parse_output_units("stewart-solve", r.units_given, units)))
        return 2;
    const char *length = units.length_name.c_str(), *angle = units.angle_name.c_str();
    std::string text(stewart_check_text_in(&report, length, angle, nullptr, 0) + 1, '\0');
    stewart_check_text_in(&report, length, angle, text.data(), text.size());
    std::fputs(text.c_str(), stdout);
    return report.valid ? 0 : 1;
}

// The drives' current rates: from the poses' jerks when the file gives them, else over t (the
// rows are a trajectory unless --static); false with a message on stderr when they fail.
bool current_rates(const Request &r, const stewart::PoseTable &table, const stewart_model *model,
                   const std::vector<double> &q, const std::vector<double> &q_dot,
                   const std::vector<double> &q_ddot, stewart_inverse_batch_outputs &columns) {
    const size_t n = table.t.size();
    char message[STEWART_MESSAGE_SIZE];
    if (!table.jerks.empty()) {
        if (stewart_inverse_batch_current_rates_from_jerks(model, r.options.fidelity, n, q.data(),
                                                           q_dot.data(), q_ddot.data(),
                                                           table.jerks.data(), &columns, message,
                                                           sizeof message) != STEWART_OK) {
            std::fprintf(stderr, "stewart-solve: %s\n", message);
            return false;
        }
    } else if (!r.at_rest &&
               stewart_inverse_batch_current_rates(model, n, table.t.data(), &columns, message,
                                                   sizeof message) != STEWART_OK) {
        std::fprintf(stderr, "stewart-solve: %s (or give --static: poses, not a trajectory)\n",
                     message);
        return false;
    }
    return true;
}

// Row j's limit check (and ranges) on its solved output; false with a message on stderr when
// the check fails.
bool check_row_limits(const Request &r, const stewart::PoseTable &table, size_t j,
                      const stewart_inverse_output &output, stewart_limits *checker,
                      LimitRow &limit_row) {
    stewart_limits_input pose{};
    std::memcpy(pose.q, table.poses[j].q, sizeof pose.q);
    if (r.report) {  // the leg classes: the derivatives the row was solved with, its forces
        pose.derivatives = 2;
        std::memcpy(pose.q_dot, table.poses[j].q_dot, sizeof pose.q_dot);
        std::memcpy(pose.q_ddot, table.poses[j].q_ddot, sizeof pose.q_ddot);
        pose.has_force = r.options.fidelity != STEWART_KINEMATIC;
        std::memcpy(pose.force, output.force, sizeof pose.force);
        if (!table.jerks.empty()) {  // the file's x_dddot..yaw_dddot: the leg jerk class too
            pose.derivatives = 3;
            std::memcpy(pose.q_dddot, &table.jerks[6 * j], sizeof pose.q_dddot);
        }
    }
    // The pose solved, so it is finite: the ranges cannot fail, the check only on leg rates
    // too large to compute.
    if (stewart_limits_check(checker, &pose, &limit_row.check) != STEWART_OK) {
        std::fprintf(stderr, "stewart-solve: row %zu (t = %g): %s\n", j + 1, table.t[j],
                     stewart_limits_message(checker));
        return false;
    }
    if (r.ranges) stewart_limits_ranges(checker, &pose, &limit_row.ranges);
    return true;
}

// Solves every row through the batch, then checks each pose's limits (and ranges); false with a
// message on stderr when a row fails.
bool solve_rows(const Request &r, const stewart::PoseTable &table, const stewart_model *model,
                stewart_inverse *inverse, stewart_limits *checker,
                std::vector<stewart_inverse_output> &outputs, std::vector<LimitRow> &limit_rows) {
    const size_t n = table.t.size();
    std::vector<double> q(6 * n), q_dot(6 * n), q_ddot(6 * n);
    for (size_t j = 0; j < n; ++j) {
        std::memcpy(&q[6 * j], table.poses[j].q, sizeof table.poses[j].q);
        std::memcpy(&q_dot[6 * j], table.poses[j].q_dot, sizeof table.poses[j].q_dot);
        std::memcpy(&q_ddot[6 * j], table.poses[j].q_ddot, sizeof table.poses[j].q_ddot);
    }
#define CLI_COLUMN(name, member, count, type, unit, description) std::vector<type> name(n *(count));
#define CLI_POINT(name, member, count, type, unit, description) columns.name = name.data();
#define CLI_ROW(name, member, count, type, unit, description) \
    if (columns.name)                                         \
        std::memcpy(&outputs[j].member, name.data() + j * (count), (count) * sizeof(type));
    STEWART_INVERSE_OUTPUT_TABLE(CLI_COLUMN)
    std::vector<int> row_status(n);
    stewart_inverse_batch_outputs columns{};
    STEWART_INVERSE_OUTPUT_TABLE(CLI_POINT)
    bool drives = false;  // without drives the drive columns are neither asked for nor written
    for (double lead : r.params.screw_lead) drives = drives || lead > 0;
#define CLI_NO_DRIVE(name, member, count, type, unit, description) columns.name = nullptr;
    if (!drives) {
        STEWART_INVERSE_DRIVE_OUTPUT_TABLE(CLI_NO_DRIVE)
    }
#undef CLI_NO_DRIVE
    columns.status = row_status.data();
    size_t failed = n;
    const stewart_status s = stewart_inverse_batch(inverse, n, q.data(), q_dot.data(),
                                                   q_ddot.data(), &columns, nullptr, &failed);
    if (s != STEWART_OK) {
        std::fprintf(stderr, "stewart-solve: row %zu (t = %g): %s: %s\n", failed + 1,
                     table.t[failed], stewart_status_name(s), stewart_inverse_message(inverse));
        return false;
    }
    if (!current_rates(r, table, model, q, q_dot, q_ddot, columns)) return false;
    for (size_t j = 0; j < n; ++j) {
        STEWART_INVERSE_OUTPUT_TABLE(CLI_ROW)
        if (!check_row_limits(r, table, j, outputs[j], checker, limit_rows[j])) return false;
    }
#undef CLI_COLUMN
#undef CLI_POINT
#undef CLI_ROW
    return true;
}

// Writes OUT.csv; 0, or 1 with a message.
int write_table(const Request &r, const stewart::PoseTable &table,
                const std::vector<stewart_inverse_output> &outputs,
                const std::vector<LimitRow> &limit_rows, bool drives) {
    FILE *out = std::fopen(r.paths[1], "w");
    if (!out) {
        std::fprintf(stderr, "stewart-solve: cannot write %s\n", r.paths[1]);
        return 1;
    }
    const int limits = limit_columns(r.limits, r.report);
    write_header(out, limits, r.ranges, drives);
    for (size_t j = 0; j < table.t.size(); ++j)
        write_row(out, table.t[j], outputs[j], limit_rows[j], limits, r.ranges, drives, r.units);
    if (std::fclose(out) != 0) {
        std::fprintf(stderr, "stewart-solve: error writing %s\n", r.paths[1]);
        return 1;
    }
    return 0;
}

// --view: the page of the run (its poses and forces) beside OUT.csv; 0, or 1 with a message.
int write_view(const Request &r, const stewart::PoseTable &table,
               const std::vector<stewart_inverse_output> &outputs) {
    std::vector<double> q, force;
    for (size_t j = 0; j < table.t.size(); ++j) {
        q.insert(q.end(), table.poses[j].q, table.poses[j].q + 6);
        force.insert(force.end(), outputs[j].force, outputs[j].force + STEWART_LEGS);
    }
    return stewart::write_view("stewart-solve", r.view_path, r.paths[1], r.params,
                               r.options.warn_condition, {table.t, q, force});
}

// The inverse of IN.csv into OUT.csv.
int run_inverse(const Request &r) {
    stewart::PoseTable table;
    const std::string read_error =
        stewart::read_pose_table(r.paths[0], table,
                                 r.at_rest ? stewart::MissingDerivatives::kZero
                                           : stewart::MissingDerivatives::kFiniteDifferences);
    if (!read_error.empty()) {
        std::fprintf(stderr, "stewart-solve: %s\n", read_error.c_str());
        return 1;
    }
    char message[STEWART_MESSAGE_SIZE];
    stewart_model *model = stewart_model_create(&r.params, message, sizeof message);
    stewart_inverse *inverse =
        model ? stewart_inverse_create(model, &r.options, message, sizeof message) : nullptr;
    stewart_limits_options limit_options;
    stewart_limits_options_default(&limit_options);
    limit_options.warn_condition = r.options.warn_condition;
    stewart_limits *checker =
        inverse ? stewart_limits_create(model, &limit_options, message, sizeof message) : nullptr;
    if (!checker) {
        std::fprintf(stderr, "stewart-solve: cannot build the model: %s\n", message);
        stewart_inverse_free(inverse);
        stewart_model_free(model);
        return 1;
    }
    // Solve everything before writing, so a failed run leaves no partial OUT.csv behind; through
    // the batch, as the Python package and the sweeps (the same numbers bit for bit).
    std::vector<stewart_inverse_output> outputs(table.t.size());
    std::vector<LimitRow> limit_rows(table.t.size());
    const bool solved = solve_rows(r, table, model, inverse, checker, outputs, limit_rows);
    bool drives = false;  // the drive columns only for a model with drives
    for (double lead : r.params.screw_lead) drives = drives || lead > 0;
    stewart_limits_free(checker);
    stewart_inverse_free(inverse);
    stewart_model_free(model);
    if (!solved) return 1;
    const int written = write_table(r, table, outputs, limit_rows, drives);
    return written || !r.view ? written : write_view(r, table, outputs);
}

}  // namespace

int main(int argc, char **argv) {
    Request r;
    const int code = parse(argc, argv, r);
    if (code >= 0) return code;
    if (r.view && (r.check || r.forward || *stewart::view_page_missing())) {
        std::fprintf(stderr, "stewart-solve: --view: %s\n",
                     *stewart::view_page_missing()
                         ? stewart::view_page_missing()
                         : "the page is of the inverse's run (for --forward's OUT.csv: "
                           "scripts/view.py --platform FILE.json OUT.csv)");
        return 2;
    }
    if (r.check) return run_check(r);
    char message[STEWART_MESSAGE_SIZE];
    if (r.forward) {
        if (!options_belong_to(r.options_given, kForwardOptions)) return 2;
        if (stewart_forward_options_check(&r.forward_options, message, sizeof message) !=
            STEWART_OK) {
            std::fprintf(stderr, "stewart-solve: %s\n", message);
            return 2;
        }
        return stewart::run_forward(r.paths[0], r.paths[1], r.params, r.forward_options,
                                    r.guess_given, r.cold, r.units);
    }
    if (!options_belong_to(r.options_given, kInverseOptions)) return 2;
    if (stewart_inverse_options_check(&r.options, message, sizeof message) != STEWART_OK) {
        std::fprintf(stderr, "stewart-solve: %s\n", message);
        return 2;
    }
    return run_inverse(r);
}
