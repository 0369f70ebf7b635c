// Geometric checks of a scene that need exact predicates: every polygon simple with positive
// area, holes strictly inside their body and apart from each other. Overlapping bodies are found
// by the cover cutter itself (build_mesh), on the exact arrangement.
#pragma once

#include <string>

#include "common/scene.h"

namespace nmm::pre {

/// Throws InputError(file, JSON path, what) on the first problem found.
void check_scene_geometry(const SceneDef& scene, const std::string& file);

}  // namespace nmm::pre
