// Time tables in a scene: a value that follows a table of (time, value) rows — a load's or a
// traction's factor, a support's velocity history, a base acceleration, an input velocity.
// Given inline ([[t, value], ...]) or as the name of a CSV file; common/time_table.h evaluates
// them (linear between rows, held outside).
#pragma once

#include <vector>

namespace nmm {

class JsonReader;

/// A time history: a value that follows a table of (time, value) rows, linearly interpolated and
/// held at its first / last value outside the table (common/time_table.h evaluates it).
struct TimeTable {
  std::vector<double> time;   ///< s, strictly increasing
  std::vector<double> value;  ///< – (a factor) or m/s² (base acceleration), one per time
  bool empty() const { return time.empty(); }
};

/// A time table: inline rows [[t, value], ...] or the name of a CSV file with rows "t,value"
/// (blank lines, lines starting with '#' and one header line of words are skipped). Times must
/// increase strictly.
TimeTable read_time_table(const JsonReader& r);

}  // namespace nmm
