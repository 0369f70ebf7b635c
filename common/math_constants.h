// Mathematical constants used across the code, once.
#pragma once

namespace nmm {

/// π to double precision (the value of M_PI, which the C++17 standard library does not promise).
constexpr double kPi = 3.14159265358979323846;

}  // namespace nmm
