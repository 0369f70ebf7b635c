// Time histories: a value that follows a table of (time, value) rows (scene.h TimeTable).
//
//   f(t) = v_i + (v_{i+1} − v_i)·(t − t_i)/(t_{i+1} − t_i)   for t_i <= t <= t_{i+1}
//   f(t) = v_0 before the first row, v_last after the last (held, not extrapolated)
#pragma once

#include "common/scene.h"

namespace nmm {

/// The table's value at time t (s); `fallback` for an empty table.
double table_value(const TimeTable& table, double t, double fallback = 1.0);

}  // namespace nmm
