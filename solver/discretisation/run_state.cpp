// Run state <-> checkpoint sections (run_state.h). Sections, in order:
//   META    u32 state layout 1 | 32-byte SHA-256 of the mesh's embedded scene | u64 counts of
//           covers, elements, loop vertices, bodies | i64 step | f64 time, dt | u8 accel_known
//   COVXY, COVU, VEL, ACC (2·pc doubles each), STRESS (3·me), LOOPXY, LOOPU (2·v)
//   POINTS  fixed, loads, measure: u64 n, then n × (i32 element, f64 x0, y0, x, y)
//   PATTERN u64 n, n × (i32, i32) element pairs, sorted
//   BODIES  [body] u8 removed, [body] i64 removed_at
//   CONTACT the contact history (contact_history.cpp)
//   (FACTOR, optional, last: the matrix of the contact solve's factorisation, system_matrix.cpp;
//    not part of the state hash — it only makes a restart precondition as the straight run did)
//   DIAG    counters for summary.json (not hashed)
//   (CARRY, optional, after DIAG: [3·block] f64 block_force, written when not empty)
// Then the effects' sections of the state they carry (effect_output.h checkpoint_sections:
// ABSORB, BOLTS, FLOW), FACTOR, the cracks' MESH and FRACTURE: written and read by their owners
// (solver/stepping/restart.cpp), each found by its tag; this file reads the state's own.
// Every vector carries its length, which must match the mesh; every index is range-checked.
#include "solver/discretisation/run_state.h"

#include <cmath>

#include "common/mesh_file.h"
#include "solver/discretisation/state_bytes.h"

namespace nmm::solve {

namespace {

constexpr std::uint32_t kStateLayout = 1;

}  // namespace

void put_points(ByteWriter& w, const std::vector<TrackedPoint>& pts) {
  w.put<std::uint64_t>(pts.size());
  for (const TrackedPoint& p : pts) {
    w.put(p.element);
    w.put(p.x0);
    w.put(p.y0);
    w.put(p.x);
    w.put(p.y);
  }
}

std::vector<TrackedPoint> get_points(ByteReader& r, std::size_t elements) {
  const std::uint64_t n = r.get<std::uint64_t>();
  if (n > (1u << 26)) r.fail("implausible number of tracked points " + std::to_string(n));
  std::vector<TrackedPoint> pts;
  for (std::uint64_t i = 0; i < n; ++i) {
    TrackedPoint p;
    p.element = r.get<std::int32_t>();
    if (p.element < 0 || static_cast<std::size_t>(p.element) >= elements)
      r.fail("tracked point in element " + std::to_string(p.element) + ", the mesh has " +
             std::to_string(elements));
    p.x0 = r.get<double>();
    p.y0 = r.get<double>();
    p.x = r.get<double>();
    p.y = r.get<double>();
    if (!std::isfinite(p.x0 + p.y0 + p.x + p.y)) r.fail("tracked point is not finite");
    pts.push_back(p);
  }
  return pts;
}

namespace {

std::string doubles(const std::vector<double>& v) {
  ByteWriter w;
  w.put_vector(v);
  return w.take();
}

}  // namespace

CheckpointSections state_to_sections(const RunState& s, const std::string& contact_history,
                                     const Mesh& mesh) {
  CheckpointSections out;
  {
    ByteWriter w;
    w.put(kStateLayout);
    w.put(mesh.scene_sha256);
    w.put<std::uint64_t>(mesh.cover_count());
    w.put<std::uint64_t>(mesh.element_count());
    w.put<std::uint64_t>(mesh.loop_vertex_count());
    w.put<std::uint64_t>(s.body_removed.size());
    w.put(s.step);
    w.put(s.time);
    w.put(s.dt);
    w.put<std::uint8_t>(s.accel_known ? 1 : 0);
    out.emplace_back("META", w.take());
  }
  out.emplace_back("COVXY", doubles(s.cover_xy));
  out.emplace_back("COVU", doubles(s.cover_u));
  out.emplace_back("VEL", doubles(s.velocity));
  out.emplace_back("ACC", doubles(s.accel));
  out.emplace_back("STRESS", doubles(s.stress));
  out.emplace_back("LOOPXY", doubles(s.loop_xy));
  out.emplace_back("LOOPU", doubles(s.loop_u));
  {
    ByteWriter w;
    put_points(w, s.fixed);
    put_points(w, s.loads);
    put_points(w, s.measure);
    out.emplace_back("POINTS", w.take());
  }
  {
    ByteWriter w;
    w.put<std::uint64_t>(s.pattern_pairs.size());
    for (const auto& [a, b] : s.pattern_pairs) {
      w.put(a);
      w.put(b);
    }
    out.emplace_back("PATTERN", w.take());
  }
  {
    ByteWriter w;
    w.put_vector(s.body_removed);
    w.put_vector(s.body_removed_at);
    out.emplace_back("BODIES", w.take());
  }
  out.emplace_back("CONTACT", contact_history);
  {
    ByteWriter w;
    w.put(s.iterations);
    w.put(s.cuts);
    w.put(s.friction_unsettled);
    w.put(s.max_capped);
    w.put(s.max_penetration);
    w.put(s.max_step_displacement);
    out.emplace_back("DIAG", w.take());
  }
  // Only when a dynamic step left one: the states of every other run keep their bytes.
  if (!s.block_force.empty()) out.emplace_back("CARRY", doubles(s.block_force));
  return out;
}

RunState state_from_sections(const CheckpointSections& sections, const Mesh& mesh,
                             const std::string& name, std::string& contact_history,
                             int dofs_per_cover, int stress_terms, std::string* factor_source) {
  static const char* const kTags[] = {"META",  "COVXY",  "COVU",   "VEL",     "ACC",
                                      "STRESS", "LOOPXY", "LOOPU", "POINTS",  "PATTERN",
                                      "BODIES", "CONTACT", "DIAG"};
  constexpr std::size_t kCount = sizeof kTags / sizeof kTags[0];
  // Optional after them: CARRY (the blocks' handed-on forces) right after DIAG; then the effects'
  // sections (read by the effects: effect_output.h restore_sections), FACTOR (the matrix of the
  // solver's factorisation, not physics) and a cracked run's MESH and FRACTURE (read by the time
  // stepper before this: restart.h), each found by its tag.
  if (sections.size() < kCount)
    throw InputError(name, "section table", "expected at least " + std::to_string(kCount) + " sections, found " +
                                                std::to_string(sections.size()));
  const std::string* carry = sections.size() > kCount && sections[kCount].first == "CARRY" ? &sections[kCount].second : nullptr;
  const std::string* factor = nullptr;
  for (std::size_t i = kCount; i < sections.size(); ++i)
    if (sections[i].first == "FACTOR") factor = &sections[i].second;
  for (std::size_t i = 0; i < kCount; ++i)
    if (sections[i].first != kTags[i])
      throw InputError(name, "section table", "section " + std::to_string(i) + " is " +
                                                  sections[i].first + ", expected " + kTags[i]);
  const std::size_t nc = mesh.cover_count(), ne = mesh.element_count(),
                    nv = mesh.loop_vertex_count();
  RunState s;
  std::uint64_t bodies = 0;
  {
    ByteReader r(sections[0].second, name, "META");
    if (r.get<std::uint32_t>() != kStateLayout) r.fail("unknown state layout");
    const auto sha = r.get<std::array<std::uint8_t, 32>>();
    if (sha != mesh.scene_sha256)
      r.fail("the checkpoint belongs to another mesh (its scene's SHA-256 differs)");
    const std::uint64_t c = r.get<std::uint64_t>(), e = r.get<std::uint64_t>(),
                        v = r.get<std::uint64_t>();
    bodies = r.get<std::uint64_t>();
    if (c != nc || e != ne || v != nv)
      r.fail("the checkpoint has " + std::to_string(c) + " covers, " + std::to_string(e) +
             " elements, " + std::to_string(v) + " loop vertices; the mesh " + std::to_string(nc) +
             ", " + std::to_string(ne) + ", " + std::to_string(nv));
    if (bodies > (1u << 24)) r.fail("implausible body count");
    s.step = r.get<std::int64_t>();
    s.time = r.get<double>();
    s.dt = r.get<double>();
    const std::uint8_t ak = r.get<std::uint8_t>();
    if (s.step < 0 || !std::isfinite(s.time) || s.time < 0 || !(s.dt > 0) || ak > 1)
      r.fail("step, time, Δt or flags out of range");
    s.accel_known = ak == 1;
    r.expect_end();
  }
  auto vec = [&](std::size_t i, std::size_t n, const char* what) {
    ByteReader r(sections[i].second, name, kTags[i]);
    std::vector<double> v = r.get_vector<double>(n, what);
    for (double x : v)
      if (!std::isfinite(x)) r.fail(std::string(what) + " holds a value that is not finite");
    r.expect_end();
    return v;
  };
  s.cover_xy = vec(1, 2 * nc, "cover positions");
  // Cover functions of another order than the run's: a clear refusal (the sizes tell).
  {
    const std::size_t bytes = sections[2].second.size();  // u64 count, then the doubles
    const std::size_t count = bytes >= 8 ? (bytes - 8) / 8 : 0;
    if (nc > 0 && count % nc == 0 && count != static_cast<std::size_t>(dofs_per_cover) * nc)
      throw InputError(name, "section COVU",
                       "the checkpoint has " + std::to_string(count / nc) +
                           " unknowns per physical cover, the run " + std::to_string(dofs_per_cover) +
                           " (a restart keeps the cover order of the run that wrote it: solver.cover_order)");
  }
  const std::size_t dpc = static_cast<std::size_t>(dofs_per_cover);
  s.cover_u = vec(2, dpc * nc, "cover displacements");
  s.velocity = vec(3, dpc * nc, "velocities");
  s.accel = vec(4, dpc * nc, "accelerations");
  s.stress = vec(5, 3 * static_cast<std::size_t>(stress_terms) * ne, "element stresses");
  s.loop_xy = vec(6, 2 * nv, "loop vertices");
  s.loop_u = vec(7, 2 * nv, "loop displacements");
  {
    ByteReader r(sections[8].second, name, "POINTS");
    s.fixed = get_points(r, ne);
    s.loads = get_points(r, ne);
    s.measure = get_points(r, ne);
    r.expect_end();
  }
  {
    ByteReader r(sections[9].second, name, "PATTERN");
    const std::uint64_t n = r.get<std::uint64_t>();
    if (n > sections[9].second.size() / 8) r.fail("pair count past the end");
    for (std::uint64_t i = 0; i < n; ++i) {
      const std::int32_t a = r.get<std::int32_t>(), b = r.get<std::int32_t>();
      if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= ne || static_cast<std::size_t>(b) >= ne)
        r.fail("element pair out of range");
      if (!s.pattern_pairs.empty() && !(s.pattern_pairs.back() < std::make_pair(a, b)))
        r.fail("element pairs not sorted");
      s.pattern_pairs.emplace_back(a, b);
    }
    r.expect_end();
  }
  {
    ByteReader r(sections[10].second, name, "BODIES");
    s.body_removed = r.get_vector<std::uint8_t>(static_cast<std::size_t>(bodies), "body flags");
    s.body_removed_at = r.get_vector<std::int64_t>(static_cast<std::size_t>(bodies), "body steps");
    for (std::size_t b = 0; b < s.body_removed.size(); ++b)
      if (s.body_removed[b] > 1 || s.body_removed_at[b] < -1 || s.body_removed_at[b] > s.step)
        r.fail("body " + std::to_string(b) + ": excavation flags out of range");
    r.expect_end();
  }
  contact_history = sections[11].second;
  if (factor_source) *factor_source = factor ? *factor : std::string();
  if (carry) {
    ByteReader r(*carry, name, "CARRY");
    s.block_force = r.get_vector<double>(3 * mesh.block_count(), "block forces");
    for (double x : s.block_force)
      if (!std::isfinite(x)) r.fail("block forces hold a value that is not finite");
    r.expect_end();
  }
  {
    ByteReader r(sections[12].second, name, "DIAG");
    s.iterations = r.get<std::uint64_t>();
    s.cuts = r.get<std::uint64_t>();
    s.friction_unsettled = r.get<std::uint64_t>();
    s.max_capped = r.get<std::uint64_t>();
    s.max_penetration = r.get<double>();
    s.max_step_displacement = r.get<double>();
    r.expect_end();
  }
  return s;
}

std::string state_hash(const RunState& s, const std::string& contact_history, const Mesh& mesh) {
  return state_hash(state_to_sections(s, contact_history, mesh));
}

std::string state_hash(const CheckpointSections& sections) {
  std::string all;
  for (const auto& [tag, data] : sections) {
    if (tag == "DIAG" || tag == "FACTOR") continue;
    all += tag;
    all.push_back('\0');
    all += data;
  }
  return to_hex(sha256(all));
}

}  // namespace nmm::solve
