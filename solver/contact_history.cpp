// Contact history <-> bytes (contact_history.h). Layout 1: u32 layout, u64 count, then per
// contact every field of Contact in declaration order (i32 indices, f64 values, u8 states and
// flags, 12 × i32 dofs, 12 × f64 cn and cs). All of it is saved, derived values included, so that
// a restarted step sees bitwise the same contacts as the straight run.
#include "contact_history.h"

#include <cmath>

#include "state_bytes.h"

namespace nmm::solve {

namespace {
constexpr std::uint32_t kContactLayout = 1;
}

std::string save_contact_history(const ContactSet& contacts) {
  ByteWriter w;
  w.put(kContactLayout);
  const std::vector<Contact>& cs = contacts.committed();
  w.put<std::uint64_t>(cs.size());
  for (const Contact& c : cs) {
    w.put(c.at.vertex);
    w.put(c.at.edge);
    w.put(c.at.elem_a);
    w.put(c.at.elem_b);
    w.put(c.at.omega);
    w.put(c.at.gap);
    w.put<std::int32_t>(c.law);
    w.put(c.length);
    w.put(static_cast<std::uint8_t>(c.state));
    w.put(static_cast<std::uint8_t>(c.start_state));
    w.put<std::uint8_t>(c.broken ? 1 : 0);
    w.put(c.shear_el);
    w.put<std::int32_t>(c.slip_sign);
    w.put(c.normal_force);
    w.put(c.friction_normal);
    w.put(c.gap);
    w.put(c.closure_k);
    w.put(c.shear_k);
    w.put(c.kn_now);
    w.put(c.ks_now);
    w.put(c.shear_force);
    w.put<std::uint8_t>(c.capped ? 1 : 0);
    w.put(c.shear);
    for (int d : c.dofs) w.put<std::int32_t>(d);
    for (double v : c.cn) w.put(v);
    for (double v : c.cs) w.put(v);
    w.put(c.gap0);
    w.put(c.shear0);
    w.put<std::int32_t>(c.group);
    w.put<std::int32_t>(c.flips);
  }
  return w.take();
}

void load_contact_history(ContactSet& contacts, const std::string& bytes, const Mesh& mesh,
                          const std::string& name) {
  ByteReader r(bytes, name, "CONTACT");
  if (r.get<std::uint32_t>() != kContactLayout) r.fail("unknown contact history layout");
  const std::uint64_t n = r.get<std::uint64_t>();
  if (n > bytes.size() / 64) r.fail("contact count " + std::to_string(n) + " past the end");
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
  cs.reserve(static_cast<std::size_t>(n));
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
    c.start_state = state(r.get<std::uint8_t>());
    c.broken = flag(r.get<std::uint8_t>());
    c.shear_el = finite(r.get<double>());
    c.slip_sign = r.get<std::int32_t>();
    if (c.slip_sign < -1 || c.slip_sign > 1) r.fail("slip direction out of range");
    c.normal_force = finite(r.get<double>());
    c.friction_normal = finite(r.get<double>());
    c.gap = finite(r.get<double>());
    c.closure_k = finite(r.get<double>());
    c.shear_k = finite(r.get<double>());
    c.kn_now = finite(r.get<double>());
    c.ks_now = finite(r.get<double>());
    c.shear_force = finite(r.get<double>());
    c.capped = flag(r.get<std::uint8_t>());
    c.shear = finite(r.get<double>());
    for (int& d : c.dofs) d = r.get<std::int32_t>();
    for (double& v : c.cn) v = finite(r.get<double>());
    for (double& v : c.cs) v = finite(r.get<double>());
    c.gap0 = finite(r.get<double>());
    c.shear0 = finite(r.get<double>());
    c.group = r.get<std::int32_t>();
    c.flips = r.get<std::int32_t>();
    cs.push_back(c);
  }
  r.expect_end();
  contacts.restore_committed(std::move(cs));
}

}  // namespace nmm::solve
