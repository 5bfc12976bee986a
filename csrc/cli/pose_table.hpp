// Reading a pose trajectory CSV and filling in missing derivatives by finite differences.
#pragma once

#include <string>
#include <vector>

#include "stewart/stewart.h"

namespace stewart {

struct PoseTable {
    std::vector<double> t;
    std::vector<stewart_pose> poses;
    std::vector<double> jerks;  // n x 6, the x_dddot..yaw_dddot columns; empty if not given
};

// The cells of one CSV line, blanks around each trimmed.
std::vector<std::string> csv_cells(const std::string &line);

// What a derivative group absent from a pose table becomes.
enum class MissingDerivatives {
    kFiniteDifferences,  // central differences of the samples: a trajectory
    kZero,               // zero: poses at rest (--static); t may then be absent (row numbers)
};

// Reads IN.csv: header `t,x,y,z,roll,pitch,yaw`, optionally `x_dot..yaw_dot` and/or
// `x_ddot..yaw_ddot`, and the jerks `x_dddot..yaw_dddot` (any column order; jerks are never
// computed: without them table.jerks is empty). A derivative group that is absent is computed by central
// finite differences of the samples (one-sided at the ends; variable spacing allowed), or is zero
// for poses at rest (which then must not give derivative columns). Returns "" on success, else a
// message naming the line and the problem.
std::string read_pose_table(const std::string &path, PoseTable &table,
                            MissingDerivatives missing = MissingDerivatives::kFiniteDifferences);

// d/dt of samples f at times t (strictly increasing): three-point differences, second order on a
// uniform grid, one-sided at the two ends. One sample: zero.
std::vector<double> finite_difference(const std::vector<double> &t, const std::vector<double> &f,
                                      int order);

}  // namespace stewart
