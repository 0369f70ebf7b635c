// The contacts of a run: detection, the transfer of each contact's history from one accepted
// step to the next, and the laws (contact_set.h). The springs, friction and states of a step are
// its ContactProblem's (contact_problem.cpp).
//
// Transfer: a vertex keeps its state while it stays against the same block (begin_step below),
// with its elastic shear, its bond and the joint law's memory; a contact that is new or was open
// takes the joint memory of its nearest closed neighbour (nearby_joint_memory).
//
// Laws: a contact takes the joint set of the joint its edge lies on (else the joint at P), else
// the scene's interface_set, else the default interface: kn = 20·E_max/h in Pa/m (a contact of
// tributary length h gets DDA's point penalty 20·E·(1 m)), ks = kn/2.5, frictionless, no cohesion
// or tension. (Shi's default point penalty is 50·E; within his recommended 10–100·E, 10–20·E is
// where the contact solve here is accurate and settles quickly: see docs/contact.md.)
#include "solver/contact/contact_set.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <tuple>
#include <utility>

#include "common/vec2.h"
#include "solver/contact/cohesive_tributary.h"
#include "solver/contact/contact_problem.h"
#include "solver/contact/contact_tolerances.h"
#include "solver/contact/tributary_length.h"

namespace nmm::solve {

ContactSet::ContactSet(const Model& model)
    : mesh_(model.mesh()), model_(model) {
  {
    // The default interface's springs: model.h PenaltyDefaults.
    const double kn = PenaltyDefaults::kInterface * model.young_max() / mesh_.mesh_size;
    ContactLaws c = contact_laws(model.scene(), kn, kn / PenaltyDefaults::kInterfaceShearRatio);
    laws_ = std::move(c.laws);
    joint_law_ = std::move(c.joint_law);
    interface_law_ = c.interface_law;
  }
  fracturing_ = model.scene().fracture.present;
  if (fracturing_)
    for (const MaterialDef& m : model.scene().materials) {
      cohesive_laws_.push_back(solve::cohesive_law(m.strength));
      cohesive_ = cohesive_ || cohesive_laws_.back().on();
    }
  active_ = !model.scene().joints.empty() || mesh_.block_count() > 1;
  if (!active_) return;
  topo_ = build_contact_topology(mesh_);
  interface_used_ = mesh_.block_count() > 1;
  std::vector<int> used = joint_law_;
  if (interface_used_) used.push_back(interface_law_);
  for (int l : used) {
    nonlinear_ |= laws_[l].normal == NormalModel::bandis_barton || !linear_shear(laws_[l]);
    memory_laws_ |= laws_[l].shear == ShearModel::barton_bandis || laws_[l].hysteresis;
    bonds_ |= laws_[l].cohesion > 0 || laws_[l].tensile > 0;
    if (laws_[l].normal == NormalModel::bandis_barton)
      topo_.master_depth = std::max(topo_.master_depth, 2.0 * laws_[l].vm);
  }
}

const CohesiveLaw& ContactSet::cohesive_law(const Contact& c) const {
  static const CohesiveLaw off;
  if (!cohesive_) return off;
  return cohesive_laws_[static_cast<std::size_t>(model_.material_of(static_cast<std::size_t>(c.at.elem_a)))];
}

const CohesiveLaw& ContactSet::cohesive_law_of_vertex(std::int32_t v) const {
  static const CohesiveLaw off;
  if (!cohesive_) return off;
  const std::size_t element = static_cast<std::size_t>(topo_.element_of[v]);
  return cohesive_laws_[static_cast<std::size_t>(model_.material_of(element))];
}

bool ContactSet::cohesive_holds(const Contact& c) const {
  return c.cohesive.on && c.cohesive.opening_max < cohesive_law(c).w_c;
}

double ContactSet::cohesive_reach() const {
  double reach = 0;
  if (!cohesive_) return reach;
  for (const Contact& c : accepted())
    if (cohesive_holds(c)) reach = std::max(reach, cohesive_law(c).w_c);
  return reach;
}

std::int32_t ContactSet::joint_of(const ContactCandidate& f) const {
  std::int32_t joint = mesh_.loop_edge_joint[f.edge];
  if (joint < 0) joint = mesh_.loop_edge_joint[f.vertex];
  if (joint < 0) joint = mesh_.loop_edge_joint[topo_.prev[f.vertex]];
  return joint;
}

void ContactSet::restore(std::vector<ContactHistory> history, std::vector<Contact> rows) {
  if (rows.empty() && !history.empty()) {
    std::vector<std::int32_t> first_of_block(mesh_.block_count(), -1);
    for (std::size_t e = mesh_.element_count(); e-- > 0;) first_of_block[mesh_.element_block[e]] = static_cast<std::int32_t>(e);
    rows.reserve(history.size());
    for (const ContactHistory& h : history) {
      Contact c;
      c.at.vertex = c.at.edge = h.vertex;
      c.at.elem_a = topo_.element_of[h.vertex];
      c.at.elem_b = first_of_block[h.block];
      c.state = c.start_state = h.state;
      c.broken = h.broken;
      c.slip_sign = h.slip_sign;
      c.shear_el = h.shear_el;
      c.normal_force = h.normal_force;
      c.joint = h.joint;
      c.cohesive = h.cohesive;
      // The depth it was at, as its gap: read back below as the depth detection lets it keep
      // against that block (closed_contacts()). At gap 0, every contact a re-cut carried over was
      // allowed no deeper than a new one (1e-3·h): a loaded corner (the flat of a disc between
      // platens, 1.5e-5 m deep at h 12.5 mm) lost its contact to the other face's vertex at the
      // same point, the platen's, with another tributary length (corner force 1.39 → 0.87 MN/m),
      // though the cut was 0.1 m away and changed no cover. A contact so carried near the
      // penetration limit is judged by what the next step adds to its depth (step_control.h).
      c.gap = -h.depth;
      rows.push_back(c);
    }
  }
  // A checkpoint keeps each contact's gap after the last solve, index-aligned with its history.
  if (rows.size() == history.size())
    for (std::size_t i = 0; i < history.size(); ++i) history[i].depth = std::max(-rows[i].gap, 0.0);
  history_ = std::move(history);
  contacts_ = std::move(rows);
  rows_accepted_ = true;
}

ClosedContacts ContactSet::closed_contacts() const {
  ClosedContacts closed;
  // A closed contact may be found as deep as closed_depth (it sank there under load, step by
  // step). A fresh crack's entry is closed too, but its faces were cut together this step: against
  // it a vertex may be no deeper than a new contact. (Counted, its vertex could take any edge of
  // its own block up to 0.3·h deep — a crack's corner 2 mm behind another face of the same
  // uncracked block, locked, threw a cover 3–7 mm at every Δt: uniaxial h 0.0625 m dynamic.)
  // Each pair with the deepest its vertex was against that block at the end of the last step.
  // Where new cracks soften, which pairs are faces that still hold tension (κ < w_c).
  std::vector<std::tuple<std::int32_t, std::int32_t, double, bool>> entries;
  entries.reserve(history_.size());
  for (const ContactHistory& h : history_) {
    if (h.state == ContactState::open || h.fresh) continue;
    const bool holds =
        cohesive_ && h.cohesive.on && h.cohesive.opening_max < cohesive_law_of_vertex(h.vertex).w_c;
    entries.emplace_back(h.vertex, h.block, h.depth, holds);
  }
  // The history is the last step's contacts, which detection gave in (vertex, block) order: most
  // steps have nothing to sort (a restart's or a re-cut's history may not be in order).
  if (!std::is_sorted(entries.begin(), entries.end())) std::sort(entries.begin(), entries.end());
  for (const auto& [v, block, depth, holds] : entries) {
    if (!closed.pairs.empty() && closed.pairs.back() == std::make_pair(v, block)) {
      closed.depth.back() = std::max(closed.depth.back(), depth);
      if (cohesive_) closed.holds.back() = static_cast<char>(closed.holds.back() || holds);
      continue;
    }
    closed.pairs.emplace_back(v, block);
    closed.depth.push_back(depth);
    if (cohesive_) closed.holds.push_back(holds);
  }
  closed.index(topo_.next.size());
  return closed;
}

namespace {

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

void ContactSet::begin_step(const std::vector<double>& xy, double d0, double shallow, double w0, double open_gap) {
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = thread_cpu_seconds();
  closed_ = closed_contacts();
  eps_ = kContactTolerances.open_gap * w0;
  const std::vector<ContactCandidate> found = detect_contacts(topo_, xy, d0, shallow, closed_, &stats_, nullptr, &candidates_,
                                                              open_gap, removed_.empty() ? nullptr : &removed_);
  stats_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  stats_.cpu_seconds += thread_cpu_seconds() - c0;

  // Transfer: a vertex keeps its state while it stays against the same block (on the same edge,
  // or having slid onto another edge of that block, e.g. the next element's along a joint); a
  // vertex has at most one contact per block (contact_detection.cpp), so (vertex, block) keys
  // the history: history_at_[v] heads a chain through history_next_ of v's entries.
  history_at_.resize(topo_.next.size(), -1);
  history_next_.resize(history_.size());
  for (std::size_t i = history_.size(); i-- > 0;) {
    history_next_[i] = history_at_[history_[i].vertex];
    history_at_[history_[i].vertex] = static_cast<std::int32_t>(i);
  }
  // The last accepted step's rows stay readable (accepted()) while this attempt rebuilds its own
  // in the other vector: no copies.
  if (rows_accepted_) std::swap(accepted_, contacts_);
  if (memory_laws_) index_closed_memory(xy);
  rows_accepted_ = false;
  std::vector<Contact>& now = contacts_;
  now.clear();
  now.reserve(found.size());
  for (const ContactCandidate& f : found) {
    if (!removed_.empty() && (removed_[f.elem_a] || removed_[f.elem_b])) continue;  // excavated
    Contact c;
    c.at = f;
    const std::int32_t joint = joint_of(f);
    c.law = joint >= 0 ? joint_law_[joint] : interface_law_;
    const std::int32_t block_a = topo_.block_of[f.elem_a], block_b = topo_.block_of[f.elem_b];
    std::int32_t at = history_at_[f.vertex];
    while (at >= 0 && history_[at].block != block_b) at = history_next_[at];
    // The other face's vertex at this point (contact_detection.cpp keeps one contact per joint
    // point): its contact against P's block is this contact seen from the other side — the same
    // gap and normal force, and the same elastic shear with the same sign (the other face's
    // edge runs the other way, and the relative displacement is reversed). When the point's
    // contact passes from one face's vertex to the other's (the kept vertex slid a fraction of a
    // µm past the end of its edge), it keeps its history instead of starting open with no
    // strength and no elastic shear (measured: 15–30 such passes per step on a settling 20 × 20
    // wall, each a friction round lost and a change in the Newton matrix).
    const double same = kContactTolerances.same_point * topo_.mesh_size;
    for (std::int32_t i = topo_.mirror_offset[f.vertex]; i < topo_.mirror_offset[f.vertex + 1]; ++i) {
      const std::int32_t m = topo_.mirrors[i];
      if (topo_.block_of[topo_.element_of[m]] != block_b ||
          length(xy[2 * m] - xy[2 * f.vertex], xy[2 * m + 1] - xy[2 * f.vertex + 1]) > same)
        continue;
      if (topo_.element_of[m] == f.elem_b) c.mirror = m;
      if (at < 0) {
        at = history_at_[m];
        while (at >= 0 && history_[at].block != block_a) at = history_next_[at];
      }
    }
    // A crack that does not split its block yet has no mirrors (they are other blocks'): where
    // new cracks soften, the vertex of the other face at P's point — an end of the edge P faces,
    // the faces being cut together — hands its history on the same way, so that a softening face
    // keeps its damage and its bond when detection keeps the other face's vertex at a point.
    if (at < 0 && cohesive_) {
      const std::int32_t q = f.omega < 0.5 ? f.edge : topo_.next[f.edge];
      if (length(xy[2 * q] - xy[2 * f.vertex], xy[2 * q + 1] - xy[2 * f.vertex + 1]) <= same) {
        at = history_at_[q];
        while (at >= 0 && history_[at].block != block_a) at = history_next_[at];
      }
    }
    // Nor does a vertex of P's own face at P's point that had no contact of its own (detection
    // kept another vertex there): where the face passes from one element to the next, or from a
    // sliver the body's boundary clips off a lattice triangle, two vertices of one face stand for
    // one point of the crack, and the one that kept the contact holds that point's damage and
    // bond. Without it the other started open with no cohesion when detection found it too, and
    // took half the point's stretch of face from the partition (cohesive_tributary.h) while
    // carrying nothing: the bar of reference/cohesive_bar.h at h 0.025 m lost 0.0054 m of its
    // 0.19 m crack at the top the step after the crack ran through, and its faces opened
    // 14.7 µm at the top and 0.14 µm at the bottom.
    if (at < 0 && cohesive_)
      for (std::size_t i = 0; i < history_.size() && at < 0; ++i) {
        const ContactHistory& h = history_[i];
        if (!h.cohesive.on || h.block != block_b || h.vertex == f.vertex ||
            topo_.block_of[topo_.element_of[h.vertex]] != block_a)
          continue;
        if (length(xy[2 * h.vertex] - xy[2 * f.vertex], xy[2 * h.vertex + 1] - xy[2 * f.vertex + 1]) <= same)
          at = static_cast<std::int32_t>(i);
      }
    // A joint's memory belongs to the joint surface (contact_set.h nearby_joint_memory()): a contact
    // that is new or was open takes that of the nearest closed contact of the same two blocks.
    const bool memory = laws_[c.law].shear == ShearModel::barton_bandis || laws_[c.law].hysteresis;
    if (memory && (at < 0 || history_[at].state == ContactState::open))
      c.joint = nearby_joint_memory(xy, f.vertex, block_a, block_b, at >= 0 ? history_[at].joint : JointMemory{});
    if (at >= 0) {
      const ContactHistory& o = history_[at];
      c.state = o.state;
      c.broken = o.broken;
      c.slip_sign = o.slip_sign;
      c.normal_force = o.normal_force;
      c.shear_el = o.shear_el;
      if (!memory || o.state != ContactState::open) c.joint = o.joint;
      c.cohesive = o.cohesive;
    }
    // A new crack's face in rock with a fracture energy softens by its cohesive law
    // (cohesive_law.h), which takes the place of the crack set's bond and peak cohesion: as far
    // as the set's law goes, the face is broken from the start (its residual cohesion applies).
    if (c.cohesive.on && !cohesive_law(c).on()) c.cohesive = {};
    if (c.cohesive.on) c.broken = true;
    // A closed contact whose gap is now positive has separated (or has moved onto an edge it
    // does not touch): it starts the step open. Kept closed, its spring would pull the faces
    // together with kn·gap — glue — and, closing the gap within the solve, never show tension.
    // A bond (unbroken, with tensile strength) holds its faces in tension: it stays closed.
    const bool bond = (!c.broken && laws_[c.law].tensile > 0) || cohesive_holds(c);
    // The gap is net of the joint's dilation (Barton–Bandis): sheared asperities hold the faces
    // apart by it, so the normal spring closes at gap = dilation.
    if (c.state != ContactState::open && f.gap - c.joint.dilation > eps_ && !bond) c.state = ContactState::open;
    c.start_state = c.state;
    c.start_shear_force = at >= 0 && c.state != ContactState::open ? history_[at].shear_force : 0.0;
    now.push_back(c);
  }
  for (const ContactHistory& h : history_) history_at_[h.vertex] = -1;
  // Tributary lengths: the joint shared among its contacts (tributary_length.cpp).
  std::vector<ContactCandidate> kept;
  kept.reserve(contacts_.size());
  for (const Contact& c : contacts_) kept.push_back(c.at);
  const std::vector<double> lengths =
      tributary_lengths(topo_, xy, kept, kContactTolerances.corner_length * topo_.mesh_size);
  for (std::size_t i = 0; i < contacts_.size(); ++i) contacts_[i].length = lengths[i];
  // Softening crack faces: the partition of each face (cohesive_tributary.h), so that what they
  // dissipate adds up to G_f × the crack's area. Only their lengths change: a run without them
  // computes what it did.
  if (std::none_of(contacts_.begin(), contacts_.end(), [](const Contact& c) { return c.cohesive.on; })) return;
  const std::vector<double> faces =
      partitioned_tributary_lengths(topo_, xy, kept, kContactTolerances.corner_length * topo_.mesh_size);
  for (std::size_t i = 0; i < contacts_.size(); ++i)
    if (contacts_[i].cohesive.on) contacts_[i].length = faces[i];
}

JointMemory ContactSet::nearby_joint_memory(const std::vector<double>& xy, std::int32_t vertex,
                                            std::int32_t block_a, std::int32_t block_b,
                                            JointMemory own_memory) const {
  // A joint's memory (shear travel, dilation, largest closure) belongs to the joint surface, not
  // to the contact that happens to carry a point of it. A contact that opens stops advancing its
  // own (it carries no load to ride the asperities with), and a new one (a corner coming onto the
  // joint, or a joint point passing to the other face's vertex once the faces have slid by more
  // than a vertex spacing) has none: either would stand open, held apart by its neighbours'
  // dilation, and never close again. Measured on a 2 m joint sheared to 0.9·τp: the last 0.4 m
  // of it stayed open from 0.7 mm of travel on, and the rest carried the load. Such a contact
  // takes the memory of the nearest closed contact between the same two blocks within a mesh
  // size (its own if there is none).
  JointMemory best = own_memory;
  const double h = topo_.mesh_size;
  double best_d = h;
  std::int64_t best_at = -1;
  const double px = xy[2 * vertex], py = xy[2 * vertex + 1];
  const auto cx = static_cast<std::int64_t>(std::floor(px / h)), cy = static_cast<std::int64_t>(std::floor(py / h));
  for (std::int64_t i = cx - 1; i <= cx + 1; ++i)
    for (std::int64_t j = cy - 1; j <= cy + 1; ++j) {
      auto k = std::lower_bound(memory_cells_.begin(), memory_cells_.end(), std::array<std::int64_t, 3>{i, j, -1});
      for (; k != memory_cells_.end() && (*k)[0] == i && (*k)[1] == j; ++k) {
        const ContactHistory& e = history_[static_cast<std::size_t>((*k)[2])];
        const std::int32_t own = topo_.block_of[topo_.element_of[e.vertex]];
        if (!((own == block_a && e.block == block_b) || (own == block_b && e.block == block_a))) continue;
        const double d = length(xy[2 * e.vertex] - px, xy[2 * e.vertex + 1] - py);
        if (d < best_d || (d == best_d && (*k)[2] < best_at)) {  // ties: the first in the history
          best_d = d;
          best_at = (*k)[2];
          best = e.joint;
        }
      }
    }
  return best;
}

void ContactSet::index_closed_memory(const std::vector<double>& xy) {
  const double h = topo_.mesh_size;
  memory_cells_.clear();
  for (std::size_t i = 0; i < history_.size(); ++i) {
    const ContactHistory& e = history_[i];
    if (e.state == ContactState::open) continue;
    memory_cells_.push_back({static_cast<std::int64_t>(std::floor(xy[2 * e.vertex] / h)),
                             static_cast<std::int64_t>(std::floor(xy[2 * e.vertex + 1] / h)),
                             static_cast<std::int64_t>(i)});
  }
  std::sort(memory_cells_.begin(), memory_cells_.end());
}

std::vector<std::string> ContactSet::effects() const {
  if (!active_) return {};
  std::vector<int> used = joint_law_;
  if (interface_used_) used.push_back(interface_law_);
  bool friction = false, cohesion = false, tension = false, bb = false, hyp = false, bbs = false;
  for (int l : used) {
    friction |= laws_[l].tan_phi > 0;
    cohesion |= laws_[l].cohesion > 0;
    tension |= laws_[l].tensile > 0;
    bb |= laws_[l].normal == NormalModel::bandis_barton;
    hyp |= laws_[l].shear == ShearModel::hyperbolic;
    bbs |= laws_[l].shear == ShearModel::barton_bandis;
  }
  std::vector<std::string> e{"contact"};
  if (friction) e.push_back("friction");
  if (cohesion) e.push_back("cohesion");
  if (tension) e.push_back("tension");
  if (bb) e.push_back("bandis_barton");
  if (hyp) e.push_back("hyperbolic");
  if (bbs) e.push_back("barton_bandis_shear");
  return e;
}

std::vector<std::pair<std::int32_t, std::int32_t>> ContactSet::element_pairs(bool accepted) const {
  const std::vector<Contact>& contacts = accepted ? this->accepted() : contacts_;
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
  pairs.reserve(contacts.size());
  for (const Contact& c : contacts) pairs.emplace_back(c.at.elem_a, c.at.elem_b);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

bool ContactSet::touching_at_start(const Contact& c) const {
  return c.start_state != ContactState::open || c.at.gap - c.joint.dilation <= eps_;
}

std::size_t ContactSet::touching_at_start() const {
  std::size_t n = 0;
  for (const Contact& c : contacts_) n += touching_at_start(c);
  return n;
}

void ContactSet::end_step(ContactProblem& step) {
  step.commit();
  history_.resize(contacts_.size());
  for (std::size_t i = 0; i < contacts_.size(); ++i) {
    const Contact& c = contacts_[i];
    history_[i] = {c.at.vertex, topo_.block_of[c.at.elem_b], c.state, c.broken,
                   static_cast<std::int8_t>(c.slip_sign), c.shear_el, c.normal_force, c.joint, std::max(-c.gap, 0.0), false,
                   c.cohesive, c.shear_force};
  }
  rows_accepted_ = true;
}

double ContactSet::max_dilation() const {
  double v = 0;
  for (const ContactHistory& h : history_) v = std::max(v, h.joint.dilation);
  return v;
}

StepPenetration ContactSet::deepening(const PenetrationAllowance& allowed) const {
  // p − max(p0, 0) per contact (gap = −p, at.gap: detection's at the step's start); a contact
  // the step lets come up adds nothing and is no deepest.
  StepPenetration judged{0, 0, 0, 0};
  double worst = -allowed.cap;  // m, p − allowed.deepest(p0) of judged.worst_*
  for (const Contact& c : contacts_) {
    const double depth = -c.gap, start = -c.at.gap, added = depth - std::max(start, 0.0);
    judged.added = std::max(judged.added, added);
    if (!(added > 0)) continue;
    judged.deepest = std::max(judged.deepest, depth);
    const double past = depth - allowed.deepest(std::max(start, 0.0));
    if (past > worst) worst = past, judged.worst_start = std::max(start, 0.0), judged.worst_end = depth;
  }
  return judged;
}

ContactSet::Totals ContactSet::totals() const {
  Totals t;
  for (const Contact& c : contacts_) {
    t.max_penetration = std::max(t.max_penetration, -c.gap);
    if (c.state == ContactState::open) continue;
    ++t.closed;
    t.capped += c.capped ? 1 : 0;
    if (!(c.length > 0)) continue;
    t.closed_length += c.length;
    t.max_normal_stress = std::max(t.max_normal_stress, c.normal_force / c.length);
    t.max_shear_stress = std::max(t.max_shear_stress, std::abs(c.shear_force) / c.length);
  }
  return t;
}

}  // namespace nmm::solve
