// Tributary lengths of softening crack faces: each crack face partitioned exactly among its
// contact points, kinks and slivers included (the rule: cohesive_tributary.cpp). Used for the
// contacts of cohesive faces only (ContactSet); every other contact keeps tributary_length.h's.
#pragma once

#include <vector>

#include "solver/contact/contact_detection.h"

namespace nmm::solve {

/// L (m) of each contact in `contacts` (the step's detection, configuration `xy`) by the
/// partition rule: the contacts along a face add up to its polyline length. Contacts whose vertex
/// stands for no length of the face they touch (a bare corner) get `corner_length` (m).
std::vector<double> partitioned_tributary_lengths(const ContactTopology& topo, const std::vector<double>& xy,
                                                  const std::vector<ContactCandidate>& contacts,
                                                  double corner_length);

}  // namespace nmm::solve
