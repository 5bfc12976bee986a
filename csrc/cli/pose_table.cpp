#include "cli/pose_table.hpp"
#include "kinematics/pose_names.hpp"
#include "util/number_text.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace stewart {

namespace {

using stewart::kPoseNames;

std::vector<std::string> split(const std::string &line) {
    std::vector<std::string> out;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) {
        const size_t b = cell.find_first_not_of(" \t\r");
        const size_t e = cell.find_last_not_of(" \t\r");
        out.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
    }
    return out;
}

int find_column(const std::vector<std::string> &header, const std::string &name) {
    for (size_t i = 0; i < header.size(); ++i)
        if (header[i] == name) return static_cast<int>(i);
    return -1;
}

// The quadratic through three samples in Newton's divided-difference form,
// p(t) = f0 + d1 (t - t0) + dd (t - t0)(t - t1): differences of values first, so a coordinate that
// does not move has exactly zero rate and acceleration however close the samples are.
struct Quadratic {
    double d1, dd, h1, h2;
    Quadratic(const double *t, const double *f) {
        h1 = t[1] - t[0];
        h2 = t[2] - t[1];
        d1 = (f[1] - f[0]) / h1;
        dd = ((f[2] - f[1]) / h2 - d1) / (h1 + h2);
    }
    // p' at the first, middle (1) or last (2) sample; p'' = 2 dd everywhere.
    double slope(int at) const { return d1 + dd * (at == 0 ? -h1 : at == 1 ? h1 : h1 + 2 * h2); }
};

}  // namespace

std::vector<std::string> csv_cells(const std::string &line) { return split(line); }

std::vector<double> finite_difference(const std::vector<double> &t, const std::vector<double> &f,
                                      int order) {
    const size_t n = t.size();
    std::vector<double> d(n, 0.0);
    if (n < 2) return d;
    if (n == 2) {
        if (order == 1) d[0] = d[1] = (f[1] - f[0]) / (t[1] - t[0]);
        return d;
    }
    for (size_t i = 0; i + 2 < n; ++i) {
        const Quadratic p(&t[i], &f[i]);
        const double value = order == 1 ? p.slope(1) : 2 * p.dd;
        d[i + 1] = value;
        // The ends take the derivative of the quadratic through the three end samples.
        if (i == 0) d[0] = order == 1 ? p.slope(0) : value;
        if (i + 3 == n) d[n - 1] = order == 1 ? p.slope(2) : value;
    }
    return d;
}

namespace {

// The rates (have[1] false) and accelerations (have[2] false) a file leaves out, by finite
// differences of its poses along t.
void differentiate_missing(const bool have[4], PoseTable &table) {
    for (int r = 1; r < 3; ++r) {
        if (have[r]) continue;
        for (int i = 0; i < 6; ++i) {
            std::vector<double> f(table.t.size());
            for (size_t j = 0; j < f.size(); ++j) f[j] = table.poses[j].q[i];
            const std::vector<double> d = finite_difference(table.t, f, r);
            for (size_t j = 0; j < f.size(); ++j)
                (r == 1 ? table.poses[j].q_dot : table.poses[j].q_ddot)[i] = d[j];
        }
    }
}

}  // namespace

std::string read_pose_table(const std::string &path, PoseTable &table, MissingDerivatives missing) {
    const bool at_rest = missing == MissingDerivatives::kZero;
    std::ifstream in(path);
    if (!in) return "cannot open " + path;
    std::string line;
    if (!std::getline(in, line))
        return path + " is empty: expected the header t,x,y,z,roll,pitch,yaw";
    if (line.compare(0, 3, "\xEF\xBB\xBF") == 0)
        line.erase(0, 3);  // a spreadsheet's byte order mark
    const std::vector<std::string> header = split(line);

    int col_t = find_column(header, "t");
    int col[4][6];
    bool have[4] = {true, true, true, true};
    int found[4] = {0, 0, 0, 0};
    const char *suffix[4] = {"", "_dot", "_ddot", "_dddot"};
    for (int r = 0; r < 4; ++r)
        for (int i = 0; i < 6; ++i) {
            col[r][i] = find_column(header, std::string(kPoseNames[i]) + suffix[r]);
            if (col[r][i] < 0) have[r] = false;
            else ++found[r];
        }
    if ((col_t < 0 && !at_rest) || !have[0])
        return path + ": the header must contain t,x,y,z,roll,pitch,yaw";
    if (at_rest && (found[1] || found[2] || found[3]))
        return path + ": --static says the poses are at rest, but the file gives the " +
               (found[1]   ? "x_dot"
                : found[2] ? "x_ddot"
                           : "x_dddot") +
               ".. columns: drop --static or those columns";
    for (int r = 1; r < 4; ++r)
        if (found[r] != 0 && found[r] != 6)
            return path + ": the " + suffix[r] + " columns must be all six (x" + suffix[r] +
                   " ... yaw" + suffix[r] + ") or none";

    table.t.clear();
    table.poses.clear();
    table.jerks.clear();
    int line_no = 1;
    while (std::getline(in, line)) {
        ++line_no;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        const std::vector<std::string> cells = split(line);
        if (cells.size() != header.size())
            return path + " line " + std::to_string(line_no) + ": " + std::to_string(cells.size()) +
                   " values for " + std::to_string(header.size()) + " columns";
        std::vector<double> v(cells.size());
        for (size_t c = 0; c < cells.size(); ++c) {
            if (!read_double(cells[c], v[c]) || !std::isfinite(v[c]))
                return path + " line " + std::to_string(line_no) + ": column " + header[c] +
                       " = '" + cells[c] + "' is not a finite number";
        }
        const double t = col_t < 0 ? static_cast<double>(table.t.size()) : v[col_t];
        if (!table.t.empty() && !(t > table.t.back()))
            return path + " line " + std::to_string(line_no) + ": t = " + cells[col_t] +
                   " does not increase";
        stewart_pose pose{};
        for (int r = 0; r < 3; ++r)
            if (have[r]) {
                double *dst = r == 0 ? pose.q : r == 1 ? pose.q_dot : pose.q_ddot;
                for (int i = 0; i < 6; ++i) dst[i] = v[col[r][i]];
            }
        table.t.push_back(t);
        table.poses.push_back(pose);
        if (have[3])
            for (int i = 0; i < 6; ++i) table.jerks.push_back(v[col[3][i]]);
    }
    if (table.t.empty()) return path + " has no data rows";
    if (!at_rest) differentiate_missing(have, table);
    return "";
}

}  // namespace stewart
