// Linear interpolation in a time table (time_table.h).
#include "common/time_table.h"

#include <algorithm>
#include <iterator>

namespace nmm {

double table_value(const TimeTable& table, double t, double fallback) {
  if (table.empty()) return fallback;
  if (t <= table.time.front()) return table.value.front();
  if (t >= table.time.back()) return table.value.back();
  // First row with time > t; t lies in [time[i-1], time[i]).
  const auto it = std::upper_bound(table.time.begin(), table.time.end(), t);
  const std::size_t i = static_cast<std::size_t>(std::distance(table.time.begin(), it));
  const double t0 = table.time[i - 1], t1 = table.time[i];
  const double v0 = table.value[i - 1], v1 = table.value[i];
  return v0 + (v1 - v0) * (t - t0) / (t1 - t0);
}

}  // namespace nmm
