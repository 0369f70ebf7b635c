// Time histories: a value that follows a table of (time, value) rows (scene.h TimeTable).
//
//   f(t) = v_i + (v_{i+1} − v_i)·(t − t_i)/(t_{i+1} − t_i)   for t_i <= t <= t_{i+1}
//   f(t) = v_0 before the first row, v_last after the last (held, not extrapolated)
//   F(t) = ∫0^t f dt'   exactly: the trapezoid on each row interval (f is linear there), f held
//          outside the rows (a support's velocity history: its travel, time_table_integral)
#pragma once

#include "common/scene.h"

namespace nmm {

/// The table's value at time t (s); `fallback` for an empty table.
double table_value(const TimeTable& table, double t, double fallback = 1.0);

/// ∫0^t f dt' of the table's value (t ≥ 0, s; the value times seconds); t for an empty table
/// (f = 1).
double table_integral(const TimeTable& table, double t);

}  // namespace nmm
