// The internal consistency of a mesh (docs/mesh-format.md, "What the reader checks"): every
// index in range, CSR offsets increasing, array sizes matching their counts, coordinates
// finite, and the relations between arrays the solver relies on (an element's covers are the
// covers of its triangle's nodes, in the same order, in the element's body). The mesh file's
// reader runs it on every file read; the tests and the fuzzers on meshes built in memory.
#pragma once

#include <string>

#include "common/mesh.h"

namespace nmm {

/// Checks the internal consistency of a mesh (index ranges, CSR offsets, counts) and throws
/// InputError(name, "section TAG", what) on the first violation.
void validate_mesh(const Mesh& mesh, const std::string& name);

}  // namespace nmm
