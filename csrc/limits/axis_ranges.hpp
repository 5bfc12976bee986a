// How far each axis of a pose can move, the other five held, before a limit
// (stewart/stewart_limits.h): a march in steps no limit can jump, then a bracketed root.
#pragma once

#include "limits/limit_check.hpp"

namespace stewart {

// Ends to within this of the first limit on each side [m or rad].
constexpr double kAxisRangeTolerance = 1e-6;

// The axis ranges at pose q (finite), as stewart_axis_ranges; never NaN.
void axis_ranges(const LimitConstants &c, const double q[6], stewart_axis_ranges &out);

}  // namespace stewart
