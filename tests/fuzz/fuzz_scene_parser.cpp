// libFuzzer target: the scene parser (common/scene.cpp) on arbitrary bytes. Any input must end
// in a SceneDef or an InputError; anything else (a crash, another exception, a sanitizer
// report) is a finding. Run: docs/fuzzing.md.
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/error.h"
#include "common/lattice.h"
#include "common/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const nmm::SceneDef scene = nmm::parse_scene(text, "fuzz.json");
    // A scene that parses must give a lattice the cutter can build (common/lattice.h).
    const nmm::Lattice lattice = nmm::make_lattice(scene.bodies, scene.mesh_size);
    if (lattice.nodes() <= 0) __builtin_trap();
  } catch (const nmm::InputError&) {
  }
  return 0;
}
