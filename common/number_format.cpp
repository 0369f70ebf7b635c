#include "common/number_format.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace nmm {

std::string format_number(double v) {
  char buf[64];
  const auto result = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, result.ptr);
}

std::string format_rough(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

std::string format_fixed(double v, int decimals) {
  char buf[400];  // %f writes every integer digit: up to 309 for the largest double
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string format_signed(double v, int decimals) {
  char buf[400];
  std::snprintf(buf, sizeof buf, "%+.*f", decimals, v);
  return buf;
}

std::string format_scientific(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*e", digits - 1, v);
  return buf;
}

std::string format_engineering(double v, const std::string& unit, int digits) {
  const std::string tail = unit.empty() ? "" : " " + unit;
  // printf writes "-nan" for a NaN whose sign bit is set: a NaN has no sign to report.
  if (std::isnan(v)) return "nan" + tail;
  if (std::isinf(v)) return (v < 0 ? "-inf" : "inf") + tail;
  if (v == 0) return "0" + tail;
  // Round first: 999.7 with three digits is 1.00e3, so the prefix must follow the rounded value.
  // strtod, not stod: a subnormal value reads back with ERANGE, which stod throws on.
  const double rounded = std::strtod(format_rough(v, digits).c_str(), nullptr);
  const int exp3 = static_cast<int>(std::floor(std::log10(std::abs(rounded)) / 3)) * 3;
  if (unit.empty()) {
    if (std::abs(rounded) >= 1e-3 && std::abs(rounded) < 1e6) return format_rough(rounded, digits);
    return format_scientific(rounded, digits);
  }
  static const char* const kPrefix[] = {"p", "n", "µ", "m", "", "k", "M", "G", "T"};
  if (exp3 < -12 || exp3 > 12) return format_scientific(rounded, digits) + tail;
  const double mantissa = rounded / std::pow(10.0, exp3);
  return format_rough(mantissa, digits) + " " + kPrefix[exp3 / 3 + 4] + unit;
}

}  // namespace nmm
