// What the outputs read of the contacts: see contact_readout.h.
#include "solver/contact/contact_readout.h"

namespace nmm::solve {

std::vector<ContactSample> contact_samples(const ContactSet& contacts, const Model& model, const RunState& s,
                                           bool open_too) {
  std::vector<ContactSample> rows;
  for (const Contact& c : contacts.contacts()) {
    if (c.state == ContactState::open && !open_too) continue;  // closed contacts carry force
    const double x = s.loop_xy[2 * c.at.vertex], y = s.loop_xy[2 * c.at.vertex + 1];
    const JointLawOutput j = joint_law_output(contacts.laws()[c.law], c.normal_force, c.length, c.joint);
    rows.push_back({x, y, static_cast<int>(c.state), c.law, -c.gap, c.shear, c.normal_force,
                    c.shear_force, c.kn_now, c.ks_now, c.length, c.at.vertex, c.at.edge,
                    model.water().pressure_at(contacts.joint_of(c.at), x, y), j.jrc_mob, j.dilation});
  }
  return rows;
}

}  // namespace nmm::solve
