// Time tables of a scene: see time_tables.h.
#include "common/scene/time_tables.h"

#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "common/error.h"
#include "common/scene/json_reader.h"
#include "common/whole_file.h"

namespace nmm {

TimeTable read_time_table(const JsonReader& r) {
  TimeTable t;
  if (r.value().is_string()) {
    const std::string path = r.as_string();
    std::string text;
    try {
      text = read_text_file(path);
    } catch (const InputError& e) {
      r.fail("cannot read the time table file \"" + path + "\": " + e.message());
    }
    std::size_t line_no = 0, start = 0;
    while (start <= text.size()) {
      std::size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      std::string line = text.substr(start, end - start);
      start = end + 1;
      ++line_no;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      const std::size_t first = line.find_first_not_of(" \t");
      if (first == std::string::npos || line[first] == '#') continue;
      double tv[2];
      const char* p = line.c_str();
      bool ok = true;
      for (int k = 0; k < 2 && ok; ++k) {
        while (*p == ' ' || *p == '\t' || (k == 1 && *p == ',') || (k == 1 && *p == ';')) ++p;
        char* q = nullptr;
        tv[k] = std::strtod(p, &q);
        ok = q != p && std::isfinite(tv[k]);
        p = q;
      }
      if (!ok) {
        if (t.time.empty() && line_no == 1) continue;  // a header line
        r.fail("time table file \"" + path + "\" line " + std::to_string(line_no) +
               ": expected two numbers \"t,value\"");
      }
      if (!t.time.empty() && !(tv[0] > t.time.back()))
        r.fail("time table file \"" + path + "\" line " + std::to_string(line_no) +
               ": times must increase strictly");
      t.time.push_back(tv[0]);
      t.value.push_back(tv[1]);
    }
    if (t.time.empty()) r.fail("time table file \"" + path + "\" holds no rows");
    return t;
  }
  r.expect_array();
  if (r.size() == 0) r.fail("a time table needs at least one row [t, value]");
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vec2 row = r[i].as_pair("a row [t, value]");
    if (!t.time.empty() && !(row.x > t.time.back())) r[i][0].fail("times must increase strictly");
    t.time.push_back(row.x);
    t.value.push_back(row.y);
  }
  return t;
}

}  // namespace nmm
