// Contact history <-> bytes (contact_history.h). Layout 3 or 4: u32 layout, u64 count, then per
// contact of the last accepted step, in this order: where it was — vertex, edge, elements A and
// B (i32), ω and the gap at detection (f64), law (i32), tributary length (f64); what lasts from
// one step to the next (ContactHistory; its block is element B's) — state (u8), broken (u8),
// elastic shear (f64), slip direction (i32), normal force (f64), the joint law's memory (shear
// travel, dilation, largest closure: f64; layout 4 then the signed shear position, f64); and
// what the last solve left
// for output: gap, shear, shear force, tangent normal and shear stiffness (f64), capped (u8).
// What a step rebuilds (unknowns, cn, cs, gap0, strengths, coupling groups) is not saved:
// begin_step() makes it again from the geometry and the history, bitwise as in the straight run.
// Layout 4 (with the position) is written when a contact's law is Barton–Bandis shear, the only
// law that has one; otherwise layout 3, so that the checkpoints and state hashes of runs without
// such joints are byte for byte those of before. A layout-3 history with a Barton–Bandis contact
// (written before the position was kept) is refused: its joints would lose their way back.
// A run whose new cracks soften (ContactSet::cohesive(): a breakable material with a fracture
// energy) writes layout 5 or 6 (3 or 4 plus, per contact after the joint memory, its cohesive
// memory: on (u8), largest effective opening and plastic slip (f64)); other runs' bytes are
// unchanged.
#include "solver/contact/contact_history.h"

#include <cmath>
#include <stdexcept>

#include "solver/discretisation/state_bytes.h"

namespace nmm::solve {

namespace {
constexpr std::uint32_t kContactLayout = 3;
constexpr std::uint32_t kContactLayoutPosition = 4;  // with the Barton–Bandis shear position
constexpr std::uint32_t kContactLayoutCohesive = 2;  // added to either: with the cohesive memory
bool barton_bandis(const ContactSet& contacts, int law) {
  return contacts.laws()[static_cast<std::size_t>(law)].shear == ShearModel::barton_bandis;
}
}

std::string save_contact_history(const ContactSet& contacts) {
  ByteWriter w;
  // The history (what lasts) with the accepted rows it came from (where, and the last solve's
  // values for output): one each per contact, in the same order.
  const std::vector<Contact>& cs = contacts.accepted();
  const std::vector<ContactHistory>& hs = contacts.history();
  if (cs.size() != hs.size()) throw std::logic_error("contact history and rows out of step");
  bool position = false;
  for (const Contact& c : cs) position = position || barton_bandis(contacts, c.law);
  const bool cohesive = contacts.cohesive();
  w.put((position ? kContactLayoutPosition : kContactLayout) + (cohesive ? kContactLayoutCohesive : 0));
  w.put<std::uint64_t>(cs.size());
  for (std::size_t i = 0; i < cs.size(); ++i) {
    const Contact& c = cs[i];
    const ContactHistory& h = hs[i];
    w.put(c.at.vertex);
    w.put(c.at.edge);
    w.put(c.at.elem_a);
    w.put(c.at.elem_b);
    w.put(c.at.omega);
    w.put(c.at.gap);
    w.put<std::int32_t>(c.law);
    w.put(c.length);
    w.put(static_cast<std::uint8_t>(h.state));
    w.put<std::uint8_t>(h.broken ? 1 : 0);
    w.put(h.shear_el);
    w.put<std::int32_t>(h.slip_sign);
    w.put(h.normal_force);
    w.put(h.joint.travel);
    w.put(h.joint.dilation);
    w.put(h.joint.closure_max);
    if (position) w.put(h.joint.position);
    if (cohesive) {
      w.put<std::uint8_t>(h.cohesive.on ? 1 : 0);
      w.put(h.cohesive.opening_max);
      w.put(h.cohesive.slip);
    }
    w.put(c.gap);
    w.put(c.shear);
    w.put(c.shear_force);
    w.put(c.kn_now);
    w.put(c.ks_now);
    w.put<std::uint8_t>(c.capped ? 1 : 0);
  }
  return w.take();
}

void load_contact_history(ContactSet& contacts, const std::string& bytes, const Mesh& mesh,
                          const std::string& name) {
  ByteReader r(bytes, name, "CONTACT");
  std::uint32_t layout = r.get<std::uint32_t>();
  const bool cohesive = layout == kContactLayout + kContactLayoutCohesive ||
                        layout == kContactLayoutPosition + kContactLayoutCohesive;
  if (cohesive) layout -= kContactLayoutCohesive;
  if (layout != kContactLayout && layout != kContactLayoutPosition) r.fail("unknown contact history layout");
  // A restart that gives the rock a fracture energy (or takes it away) reads either: faces cut
  // before without it do not soften, and a memory the rock no longer has is dropped
  // (ContactSet::begin_step).
  const bool position = layout == kContactLayoutPosition;
  const std::uint64_t n = r.get<std::uint64_t>();
  if (n > bytes.size() / 40) r.fail("contact count " + std::to_string(n) + " past the end");
  const std::int64_t nv = static_cast<std::int64_t>(mesh.loop_vertex_count());
  const std::int64_t ne = static_cast<std::int64_t>(mesh.element_count());
  const std::int64_t nl = static_cast<std::int64_t>(contacts.laws().size());
  auto in = [&](std::int64_t v, std::int64_t hi, const char* what) {
    if (v < 0 || v >= hi) r.fail(std::string(what) + " " + std::to_string(v) + " out of range");
  };
  auto finite = [&](double v) {
    if (!std::isfinite(v)) r.fail("a value is not finite");
    return v;
  };
  auto state = [&](std::uint8_t s) {
    if (s > 2) r.fail("contact state " + std::to_string(s) + " out of range");
    return static_cast<ContactState>(s);
  };
  auto flag = [&](std::uint8_t b) {
    if (b > 1) r.fail("flag out of range");
    return b == 1;
  };
  std::vector<Contact> cs;
  std::vector<ContactHistory> hs;
  cs.reserve(static_cast<std::size_t>(n));
  hs.reserve(static_cast<std::size_t>(n));
  for (std::uint64_t i = 0; i < n; ++i) {
    Contact c;
    c.at.vertex = r.get<std::int32_t>();
    in(c.at.vertex, nv, "contact vertex");
    c.at.edge = r.get<std::int32_t>();
    in(c.at.edge, nv, "contact edge");
    c.at.elem_a = r.get<std::int32_t>();
    in(c.at.elem_a, ne, "contact element");
    c.at.elem_b = r.get<std::int32_t>();
    in(c.at.elem_b, ne, "contact element");
    c.at.omega = finite(r.get<double>());
    c.at.gap = finite(r.get<double>());
    c.law = r.get<std::int32_t>();
    in(c.law, nl, "contact law");
    c.length = finite(r.get<double>());
    c.state = state(r.get<std::uint8_t>());
    c.start_state = c.state;
    c.broken = flag(r.get<std::uint8_t>());
    c.shear_el = finite(r.get<double>());
    c.slip_sign = r.get<std::int32_t>();
    if (c.slip_sign < -1 || c.slip_sign > 1) r.fail("slip direction out of range");
    c.normal_force = finite(r.get<double>());
    c.joint.travel = finite(r.get<double>());
    c.joint.dilation = finite(r.get<double>());
    c.joint.closure_max = finite(r.get<double>());
    if (position) {
      c.joint.position = finite(r.get<double>());
    } else if (barton_bandis(contacts, c.law)) {
      r.fail("a Barton–Bandis joint without its shear position (written by an older nmm-solve)");
    }
    if (cohesive) {
      c.cohesive.on = flag(r.get<std::uint8_t>());
      c.cohesive.opening_max = finite(r.get<double>());
      c.cohesive.slip = finite(r.get<double>());
    }
    c.gap = finite(r.get<double>());
    c.shear = finite(r.get<double>());
    c.shear_force = finite(r.get<double>());
    c.kn_now = finite(r.get<double>());
    c.ks_now = finite(r.get<double>());
    c.capped = flag(r.get<std::uint8_t>());
    hs.push_back({c.at.vertex, mesh.element_block[c.at.elem_b], c.state, c.broken,
                  static_cast<std::int8_t>(c.slip_sign), c.shear_el, c.normal_force, c.joint, 0.0, false, c.cohesive,
                  c.shear_force});
    cs.push_back(c);
  }
  r.expect_end();
  contacts.restore(std::move(hs), std::move(cs));
}

}  // namespace nmm::solve
