// The bolts as an effect of the step: see bolt_effect.h.
#include "solver/reinforcement/bolt_effect.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "solver/discretisation/state_bytes.h"
#include "solver/reinforcement/bolt_layout.h"
#include "solver/reinforcement/bolt_readout.h"

namespace nmm::solve {

namespace {

constexpr std::uint32_t kBoltLayout = 1;

// Per bolt: u8 type, f64 ax ay bx by, i64 installed step, u8 broken, u8 yielded, f64 max axial
// force, f64 plastic work, its nodes (as POINTS), then axial [segments], slip and bond [nodes
// or 0] as vectors.
std::string put_bolts(const std::vector<BoltState>& bolts) {
  ByteWriter w;
  w.put(kBoltLayout);
  w.put<std::uint64_t>(bolts.size());
  for (const BoltState& b : bolts) {
    w.put(b.type);
    for (double v : {b.ax, b.ay, b.bx, b.by}) w.put(v);
    w.put(b.installed_step);
    w.put(b.broken);
    w.put(b.yielded);
    w.put(b.max_axial);
    w.put(b.plastic_work);
    put_points(w, b.nodes);
    w.put_vector(b.axial);
    w.put_vector(b.slip);
    w.put_vector(b.bond);
  }
  return w.take();
}

std::vector<BoltState> get_bolts(const std::string& bytes, std::size_t elements, std::int64_t step,
                                 const std::string& name) {
  ByteReader r(bytes, name, "BOLTS");
  if (r.get<std::uint32_t>() != kBoltLayout) r.fail("unknown bolt layout");
  const std::uint64_t n = r.get<std::uint64_t>();
  if (n > bytes.size()) r.fail("implausible number of bolts " + std::to_string(n));
  std::vector<BoltState> out(static_cast<std::size_t>(n));
  for (BoltState& b : out) {
    b.type = r.get<std::uint8_t>();
    b.ax = r.get<double>();
    b.ay = r.get<double>();
    b.bx = r.get<double>();
    b.by = r.get<double>();
    b.installed_step = r.get<std::int64_t>();
    b.broken = r.get<std::uint8_t>();
    b.yielded = r.get<std::uint8_t>();
    b.max_axial = r.get<double>();
    b.plastic_work = r.get<double>();
    if (b.type > 1 || b.broken > 1 || b.yielded > 1 || b.installed_step < 0 || b.installed_step > step)
      r.fail("bolt type, flags or installation step out of range");
    b.nodes = get_points(r, elements);
    b.axial = r.get_vector<double>(SIZE_MAX, "axial forces");
    b.slip = r.get_vector<double>(SIZE_MAX, "slips");
    b.bond = r.get_vector<double>(SIZE_MAX, "bond forces");
    const std::size_t nodes = b.nodes.size();
    const std::size_t per_node = b.type == 1 ? nodes : 0;
    if (nodes < 2 || b.axial.size() != nodes - 1 || b.slip.size() != per_node || b.bond.size() != per_node ||
        (b.type == 0 && nodes != 2))
      r.fail("a bolt's nodes, segments and slips do not match");
    double sum = b.ax + b.ay + b.bx + b.by + b.max_axial + b.plastic_work;
    for (const auto* v : {&b.axial, &b.slip, &b.bond})
      for (double x : *v) sum += x;
    if (!std::isfinite(sum)) r.fail("a bolt holds a value that is not finite");
  }
  r.expect_end();
  return out;
}

}  // namespace

void BoltEffect::checkpoint_sections(const RunState& s, const Mesh& /*mesh*/, CheckpointSections& sections) const {
  if (!s.bolts.empty()) sections.emplace_back("BOLTS", put_bolts(s.bolts));
}

void BoltEffect::restore_sections(const CheckpointSections& sections, const Mesh& mesh, const std::string& name,
                                  RunState& s) const {
  const auto it = std::find_if(sections.begin(), sections.end(), [](const auto& x) { return x.first == "BOLTS"; });
  if (it != sections.end()) s.bolts = get_bolts(it->second, mesh.element_count(), s.step, name);
}

bool BoltEffect::install(RunState& s, const std::string& /*name*/) {
  // The state's bolts where the scene still has them, the others installed now (bolt_layout.h).
  // A bolt installed now (or one dropped) changes the system's size: a checkpoint's
  // factorisation no longer fits. (A bolt's points are the scene's: errors name the scene.)
  const std::vector<BoltState> carried = s.bolts;
  s.bolts = bolts_for_run(model_.scene(), model_.mesh(), s, carried, scene_name_);
  return s.bolts.size() == carried.size() &&
         std::equal(carried.begin(), carried.end(), s.bolts.begin(), [](const BoltState& a, const BoltState& b) {
           return a.type == b.type && a.ax == b.ax && a.ay == b.ay && a.bx == b.bx && a.by == b.by &&
                  a.installed_step == b.installed_step;
         });
}

void BoltEffect::carry_over(const MeshPieces& from, RunState& s) const {
  retie_bolts(from.old, model_.mesh(), from.element_parent, from.vertex_parent, s.bolts);
}

void BoltEffect::number(const RunState& s, int first_unknown, std::size_t first_group) {
  bolts_.number(s.bolts, first_unknown);
  first_group_ = first_group;
  count_ = s.bolts.size();
}

void BoltEffect::add_groups(const RunState& /*s*/, std::vector<int>& offsets, std::vector<int>& dofs) const {
  bolts_.add_groups(offsets, dofs);
}

Outcome BoltEffect::begin_step(EffectStep& step) {
  bolts_.begin_step(step.context.config, step.s, step.context.removed);
  return {};
}

void BoltEffect::add_at_rest(EffectStep& rest) {
  bolts_.begin_step(rest.context.config, rest.s, rest.context.removed);
  bolts_.assemble(rest.system, rest.rhs, first_group_);
}

void BoltEffect::assemble(EffectStep& step) { bolts_.assemble(step.system, step.rhs, first_group_); }

Outcome BoltEffect::not_settled(double t) const {
  return Outcome::stop(StopCode::bolts_not_settled,
                       "the bolts' springs were still switching between elastic and yielding or slipping after " +
                           std::to_string(BoltSystem::kMaxRounds) + " solves of the step",
                       t);
}

void BoltEffect::commit(EffectStep& step, const Eigen::VectorXd& d) {
  bolts_.commit(d, step.context.config, step.s.bolts);
}

void BoltEffect::summarise(const RunState& s, nlohmann::json& summary) const {
  if (s.bolts.empty()) return;
  nlohmann::json bolts = nlohmann::json::array();
  for (std::size_t b = 0; b < s.bolts.size(); ++b) {
    const BoltState& bs = s.bolts[b];
    double slip = 0;
    for (double x : bs.slip) slip = std::max(slip, std::abs(x));
    nlohmann::json j = {{"bolt", b},
                        {"max_axial_force", bs.max_axial},
                        {"yielded", bs.yielded != 0},
                        {"broken", bs.broken != 0},
                        {"type", bs.type == 0 ? "anchored" : "grouted"},
                        {"installed_step", bs.installed_step}};
    if (bs.type != 0) j["max_slip_m"] = slip;
    bolts.push_back(j);
  }
  summary["bolts"] = bolts;
}

void BoltEffect::write_outputs(OutputStep& out) const {
  const std::vector<BoltState>& bolts = out.state.bolts;
  if (bolts.empty()) return;
  OutputTable& t = out.tables.table("bolts.csv", "step,time,bolt,s,axial_force,bond_force,x,y,ux,uy");
  for (std::size_t b = 0; b < bolts.size(); ++b)
    for (const BoltReading& r : bolt_readout(model_.scene().bolts[b], bolts[b])) {
      t.row(out.step, out.time);
      t.add_index(static_cast<std::int64_t>(b));
      for (double v : {r.s, r.axial, r.bond, r.x, r.y, r.ux, r.uy}) t.add(v);
      t.end_row();
    }
}

void BoltEffect::energy_state(const EnergyState& e, EnergyTerms& t) const {
  const std::vector<BoltDef>& defs = e.model.scene().bolts;
  for (std::size_t b = 0; b < e.s.bolts.size(); ++b) t.stored += bolt_elastic_energy(defs[b], e.s.bolts[b]);
  for (const BoltState& b : e.s.bolts) t.friction += b.plastic_work;
}

}  // namespace nmm::solve
