// The cracks of a run and their tips as NumPy arrays: see crack_arrays.h.
#include "python/crack_arrays.h"

#include <cmath>

#include "common/math_constants.h"
#include "solver/stepping/fracture_effect.h"

namespace nmm::python {

namespace {

/// A column of `rows` as a NumPy array of `get`'s type.
template <class Row, class Get>
py::array column(const std::vector<Row>& rows, Get get) {
  using T = decltype(get(rows.front()));
  py::array_t<T> a(static_cast<py::ssize_t>(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) a.mutable_at(static_cast<py::ssize_t>(i)) = get(rows[i]);
  return std::move(a);
}

}  // namespace

py::dict crack_segments(const solve::RunView& run) {
  using solve::CrackSegment;
  const std::vector<CrackSegment>& s = fracture_of(run).segments();
  py::dict d;
  d["x0"] = column(s, [](const CrackSegment& c) { return c.a_now.x; });
  d["y0"] = column(s, [](const CrackSegment& c) { return c.a_now.y; });
  d["x1"] = column(s, [](const CrackSegment& c) { return c.b_now.x; });
  d["y1"] = column(s, [](const CrackSegment& c) { return c.b_now.y; });
  d["mode"] = column(s, [](const CrackSegment& c) {
    return static_cast<std::int8_t>(c.mode == solve::CrackMode::tensile ? 0 : 1);
  });
  d["crack"] = column(s, [](const CrackSegment& c) { return static_cast<std::int32_t>(c.crack); });
  d["step"] = column(s, [](const CrackSegment& c) { return static_cast<std::int64_t>(c.step); });
  d["time"] = column(s, [](const CrackSegment& c) { return c.time; });
  return d;
}

py::dict crack_tips(const solve::RunView& run, solve::CrackTipFinder& finder) {
  using solve::TipReading;
  const std::vector<TipReading> t = solve::read_crack_tips(run, finder);
  py::dict d;
  d["tip"] = column(t, [](const TipReading& r) { return static_cast<std::int32_t>(r.tip); });
  d["x"] = column(t, [](const TipReading& r) { return r.x; });
  d["y"] = column(t, [](const TipReading& r) { return r.y; });
  d["k1"] = column(t, [](const TipReading& r) { return r.k1; });
  d["k2"] = column(t, [](const TipReading& r) { return r.k2; });
  d["angle_deg"] = column(t, [](const TipReading& r) { return r.angle_deg; });
  std::vector<double> dir;
  for (const TipReading& r : t) dir.insert(dir.end(), {std::cos(r.angle_deg * kPi / 180), std::sin(r.angle_deg * kPi / 180)});
  d["direction"] = copy(dir, {static_cast<py::ssize_t>(t.size()), 2});
  d["radius"] = column(t, [](const TipReading& r) { return r.radius; });
  return d;
}

}  // namespace nmm::python
