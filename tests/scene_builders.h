// The reference problems' scenes under their former names (nmm::test::), for code that still
// includes this header (bench/contact_bench.cpp). They live in reference/ (nmm_reference):
// include scene_pieces.h, sliding_block.h or brick_wall.h and use nmm::reference:: instead.
#pragma once

#include "reference/brick_wall.h"
#include "reference/scene_pieces.h"
#include "reference/sliding_block.h"

namespace nmm::test {

using reference::box;
using reference::brick_wall;
using reference::held_along;
using reference::interface_scene;
using reference::sliding_block_incline;
using reference::sliding_block_tilted;

}  // namespace nmm::test
