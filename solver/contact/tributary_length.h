// Tributary joint lengths of the step's contacts: the share of a joint (or of two touching faces)
// that each contact point stands for, so that the contacts along a joint add up to its length
// whatever the meshes on its two faces. See tributary_length.cpp for the rule.
#pragma once

#include <vector>

#include "solver/contact/contact_detection.h"

namespace nmm::solve {

/// L (m) of each contact in `contacts` (the step's detection, configuration `xy`): contacts whose
/// vertex stands for no length of the face they touch (a bare corner) get `corner_length` (m).
std::vector<double> tributary_lengths(const ContactTopology& topo, const std::vector<double>& xy,
                                      const std::vector<ContactCandidate>& contacts,
                                      double corner_length);

}  // namespace nmm::solve
