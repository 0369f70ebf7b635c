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

double table_integral(const TimeTable& table, double t) {
  if (table.empty()) return t;
  // Pieces of [0, t]: before the first row (f = v_0), between rows (linear), after the last.
  double sum = 0, a = 0;
  auto add = [&](double b) {  // ∫a^b f, f linear on [a, b]
    if (b <= a) return;
    sum += 0.5 * (table_value(table, a) + table_value(table, b)) * (b - a);
    a = b;
  };
  for (double row : table.time) {
    if (row >= t) break;
    add(row);
  }
  add(t);
  return sum;
}

}  // namespace nmm
