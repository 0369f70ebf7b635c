// The re-cut against the full cut: see recut_check.h.
#include "solver/fracture/recut_check.h"

#include <cstdio>
#include <cstdlib>

#include "common/mesh_compare.h"
#include "common/mesh_file.h"
#include "preprocess/cover_cutter.h"

namespace nmm::solve {

bool recut_check_enabled() {
  static const bool on = [] {
    const char* v = std::getenv("NMM_CHECK_RECUT");
    return v != nullptr && std::string(v) != "0";
  }();
  return on;
}

std::string recut_difference(const Mesh& before, const Mesh& recut, const SceneDef& cracked,
                             const std::string& scene_name, pre::GrowingCut& full_cut) {
  Mesh full = full_cut.cut(cracked, scene_name);
  std::string diff = mesh_difference(recut, full);
  const char* dump = std::getenv("NMM_CHECK_RECUT_DUMP");
  if (diff.empty() || dump == nullptr) return diff;
  const std::string prefix = dump;
  // The run's scene and its digest, as the re-cut carries them (a mesh file without them is not
  // one nmm-inspect reads: the digest must be the scene's).
  full.tool = "nmm-solve";
  full.scene_file = before.scene_file;
  full.scene_text = before.scene_text;
  full.scene_sha256 = before.scene_sha256;
  write_mesh_file(before, prefix + ".before.nmm");
  write_mesh_file(recut, prefix + ".recut.nmm");
  write_mesh_file(full, prefix + ".full.nmm");
  if (FILE* f = std::fopen((prefix + ".joints.txt").c_str(), "w")) {
    for (std::size_t j = 0; j < cracked.joints.size(); ++j)
      for (std::size_t k = 0; k + 1 < cracked.joints[j].points.size(); ++k)
        std::fprintf(f, "%zu %.17g %.17g %.17g %.17g\n", j, cracked.joints[j].points[k].x, cracked.joints[j].points[k].y,
                     cracked.joints[j].points[k + 1].x, cracked.joints[j].points[k + 1].y);
    std::fclose(f);
  }
  return diff;
}

}  // namespace nmm::solve
