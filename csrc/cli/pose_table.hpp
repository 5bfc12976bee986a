// Reading a pose trajectory CSV and filling in missing derivatives by finite differences.
#pragma once

#include <string>
#include <vector>

#include "stewart/stewart.h"

namespace stewart {

struct PoseTable {
    std::vector<double> t;
    std::vector<stewart_pose> poses;
};

// The cells of one CSV line, blanks around each trimmed.
std::vector<std::string> csv_cells(const std::string &line);

// Reads IN.csv: header `t,x,y,z,roll,pitch,yaw`, optionally `x_dot..yaw_dot` and/or
// `x_ddot..yaw_ddot` (any column order). A derivative group that is absent is computed by central
// finite differences of the samples (one-sided at the ends; variable spacing allowed). Returns ""
// on success, else a message naming the line and the problem.
std::string read_pose_table(const std::string &path, PoseTable &table);

// d/dt of samples f at times t (strictly increasing): three-point differences, second order on a
// uniform grid, one-sided at the two ends. One sample: zero.
std::vector<double> finite_difference(const std::vector<double> &t, const std::vector<double> &f,
                                      int order);

}  // namespace stewart
