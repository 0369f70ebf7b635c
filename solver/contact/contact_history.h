// The contact history in a checkpoint: what the last accepted step left for the next
// (ContactSet::history()) with that step's contacts (ContactSet::accepted(): where they were and
// the last solve's values, for output). The one place that knows their layout on disk: a change
// needs only these two functions adapted (and the layout number raised, so that older
// checkpoints are refused rather than misread).
#pragma once

#include <string>

#include "solver/contact/contact_set.h"

namespace nmm::solve {

/// Bytes of the CONTACT section.
std::string save_contact_history(const ContactSet& contacts);

/// Restores the contacts from a CONTACT section, checking every index against the mesh and
/// the laws; InputError(name, "section CONTACT byte N", what) on damaged data.
void load_contact_history(ContactSet& contacts, const std::string& bytes, const Mesh& mesh,
                          const std::string& name);

}  // namespace nmm::solve
