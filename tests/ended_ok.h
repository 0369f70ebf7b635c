// The test predicate for a step or run that must end ok (common/outcome.h): with
// ASSERT_PRED1(ended_ok, st.run_until(...)) a failure prints the outcome's code and reason;
// text() is the same for a printed line.
#pragma once

#include <sstream>
#include <string>

#include "common/outcome.h"

namespace nmm::test {

inline bool ended_ok(const Outcome& o) { return o.ok(); }

/// "ok", or the code's name and the reason: for a test's printed line.
inline std::string text(const Outcome& o) {
  std::ostringstream os;
  os << o;
  return os.str();
}

}  // namespace nmm::test
