// Numbers in messages: exact where the user typed them, rough where they are estimates.
#pragma once

#include <string>

namespace nmm {

/// Shortest text that reads back as the same double: "0.001", "1e+10", "0.49999999", "inf".
std::string format_number(double v);

/// printf-style "%.<digits>g", for rough figures such as an estimated triangle count.
std::string format_rough(double v, int digits);

}  // namespace nmm
