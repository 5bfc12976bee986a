#include "cli/forward_table.hpp"
#include "kinematics/pose_names.hpp"
#include "util/number_text.hpp"

#include "cli/pose_table.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <fstream>
#include <vector>

namespace stewart {

namespace {

const char *const kGroups[3] = {"L", "L_dot", "L_ddot"};
using stewart::kPoseNames;

struct Row {
    int line;
    double t;
    std::array<double, 18> values;  // L1..L6, L_dot1..L_dot6, L_ddot1..L_ddot6
};

struct Table {
    bool has[3] = {true, false, false};
    std::vector<Row> rows;
};

// "IN.csv line 7", for messages.
std::string where(const std::string &path, int line) {
    return path + " line " + std::to_string(line);
}

// Reads and checks the whole table; "" or a message naming the line and the leg.
std::string read_table(const std::string &path, Table &table) {
    std::ifstream in(path);
    if (!in) return "cannot open " + path;
    std::string line;
    if (!std::getline(in, line)) return path + " is empty: expected the header t,L1,..,L6";
    const std::vector<std::string> header = csv_cells(line);
    int col_t = -1, col[3][6], found[3] = {0, 0, 0};
    for (int g = 0; g < 3; ++g)
        for (int k = 0; k < 6; ++k) col[g][k] = -1;
    for (size_t c = 0; c < header.size(); ++c) {
        if (header[c] == "t") col_t = static_cast<int>(c);
        for (int g = 0; g < 3; ++g)
            for (int k = 0; k < 6; ++k)
                if (header[c] == kGroups[g] + std::to_string(k + 1))
                    col[g][k] = static_cast<int>(c), ++found[g];
    }
    if (col_t < 0 || found[0] != 6) return path + ": the header must contain t,L1,L2,L3,L4,L5,L6";
    for (int g = 1; g < 3; ++g) {
        if (found[g] != 0 && found[g] != 6)
            return path + ": the " + kGroups[g] + " columns must be all six (" + kGroups[g] +
                   "1 .. " + kGroups[g] + "6) or none";
        table.has[g] = found[g] == 6;
    }
    if (table.has[2] && !table.has[1])
        return path + ": the L_ddot columns need the L_dot columns too";
    int line_no = 1;
    while (std::getline(in, line)) {
        ++line_no;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        const std::vector<std::string> cells = csv_cells(line);
        if (cells.size() != header.size())
            return where(path, line_no) + ": " + std::to_string(cells.size()) + " values for " +
                   std::to_string(header.size()) + " columns";
        auto number = [&](int c, double &v) {
            return read_double(cells[c], v) && std::isfinite(v);
        };
        Row row{line_no, 0, {}};
        if (!number(col_t, row.t))
            return where(path, line_no) + ": t = '" + cells[col_t] + "' is not a finite number";
        if (!table.rows.empty() && !(row.t > table.rows.back().t))
            return where(path, line_no) + ": t = " + cells[col_t] + " does not increase";
        for (int g = 0; g < 3; ++g)
            for (int k = 0; k < 6 && table.has[g]; ++k)
                if (!number(col[g][k], row.values[6 * g + k]))
                    return where(path, line_no) + ": leg " + std::to_string(k + 1) + ": " +
                           header[col[g][k]] + " = '" + cells[col[g][k]] +
                           "' is not a finite number";
        table.rows.push_back(row);
    }
    if (table.rows.empty()) return path + " has no data rows";
    return "";
}

// The output header: the pose, the derivatives given, the statistics.
void write_header(FILE *out, const Table &table) {
    std::fprintf(out, "t");
    const char *suffix[3] = {"", "_dot", "_ddot"};
    for (int g = 0; g < 3; ++g)
        for (int i = 0; i < 6 && table.has[g]; ++i)
            std::fprintf(out, ",%s%s", kPoseNames[i], suffix[g]);
    std::fprintf(out, ",iterations,residual,condition\n");
}

// One output row, every digit kept.
void write_row(FILE *out, const Table &table, double t, const stewart_forward_output &r,
               const OutputUnits &u) {
    std::fprintf(out, "%.17g", t);
    const double *groups[3] = {r.pose.q, r.pose.q_dot, r.pose.q_ddot};
    for (int g = 0; g < 3; ++g)
        for (int i = 0; i < 6 && table.has[g]; ++i)
            std::fprintf(out, ",%.17g", groups[g][i] * (i < 3 ? u.length : u.angle));
    std::fprintf(out, ",%d,%.17g,%.17g\n", r.iterations, r.residual * u.length, r.condition);
}

}  // namespace

int run_forward(const char *in_path, const char *out_path, const stewart_params &params,
                const stewart_forward_options &options, const double *guess, bool cold,
                const OutputUnits &units) {
    Table table;
    const std::string error = read_table(in_path, table);
    if (!error.empty()) {
        std::fprintf(stderr, "stewart-solve: %s\n", error.c_str());
        return 1;
    }
    char message[STEWART_MESSAGE_SIZE];
    stewart_model *model = stewart_model_create(&params, message, sizeof message);
    stewart_forward *forward =
        model ? stewart_forward_create(model, &options, message, sizeof message) : nullptr;
    if (!forward) {
        std::fprintf(stderr, "stewart-solve: cannot build the model: %s\n", message);
        stewart_model_free(model);
        return 1;
    }
    // Solve everything before writing, so a failed run leaves no partial OUT.csv behind.
    std::vector<stewart_forward_output> results(table.rows.size());
    int status = 0, warned[3] = {0, 0, 0};
    stewart_forward_input in{};
    in.derivatives = table.has[2] ? 2 : table.has[1] ? 1 : 0;
    if (guess) std::memcpy(in.guess, guess, sizeof in.guess);
    for (size_t j = 0; j < table.rows.size() && status == 0; ++j) {
        const Row &row = table.rows[j];
        in.time = row.t;
        std::memcpy(in.lengths.length, row.values.data(), sizeof in.lengths.length);
        if (table.has[1])
            std::memcpy(in.lengths.length_rate, row.values.data() + 6,
                        sizeof in.lengths.length_rate);
        if (table.has[2])
            std::memcpy(in.lengths.length_accel, row.values.data() + 12,
                        sizeof in.lengths.length_accel);
        in.use_guess = guess && (cold || j == 0);
        const stewart_status s = cold ? stewart_forward_solve_cold(forward, &in, &results[j])
                                      : stewart_forward_solve(forward, &in, &results[j]);
        if (s != STEWART_OK) {
            std::fprintf(stderr, "stewart-solve: %s (t = %g): %s: %s\n",
                         where(in_path, row.line).c_str(), row.t, stewart_status_name(s),
                         stewart_forward_message(forward));
            status = 1;
        }
        const int w = results[j].warnings;
        warned[0] += (w & STEWART_WARN_STROKE) != 0;
        warned[1] += (w & STEWART_WARN_NEAR_SINGULAR) != 0;
    }
    stewart_forward_free(forward);
    stewart_model_free(model);
    if (status != 0) return status;
    if (warned[0] || warned[1])
        std::fprintf(stderr,
                     "stewart-solve: warning: %d rows with a length outside the stroke, "
                     "%d rows near a singular pose (condition > %g)\n",
                     warned[0], warned[1], options.warn_condition);
    FILE *out = std::fopen(out_path, "w");
    if (!out) {
        std::fprintf(stderr, "stewart-solve: cannot write %s\n", out_path);
        return 1;
    }
    write_header(out, table);
    for (size_t j = 0; j < table.rows.size(); ++j)
        write_row(out, table, table.rows[j].t, results[j], units);
    if (std::fclose(out) != 0) {
        std::fprintf(stderr, "stewart-solve: error writing %s\n", out_path);
        return 1;
    }
    return 0;
}

}  // namespace stewart
