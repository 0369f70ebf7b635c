// Preprocessing generated joint networks (issue 14): time against joints and elements, and peak
// memory, up to 10,000 joints (and one case of 20,000) in a 200 m × 200 m model at mesh size 1 m.
//
//   dfn_bench [--quick] [--max-joints N] [--csv FILE]
//
// Scene: one 200 m × 200 m body, mesh size 1 m (~92,000 triangles), two generated Poisson sets
// (the nmm-preprocess pipeline, from scene text): "a" at 30° (von Mises κ = 10) and "b" at 120°
// (κ = 10), exponential trace lengths of mean 8 m, each set with half the target joint count
// (P21 = (N/2)·8 m / 40,000 m² each), set b ending at set a's joints with probability 0.5 (the
// termination search runs). Each case runs in a child process (fork) so that its peak resident
// memory, ru_maxrss from wait4, is its own. One CSV row per case: joints generated, elements,
// blocks, and seconds in generation (generate + explicit scene + parse), checks, cutting
// (build_mesh; also its arrangement, labelling and covers phases) and writing the mesh file, the
// child's CPU seconds (user + system: robust to a busy machine, where wall time includes waiting).
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "preprocess/cover_cutter.h"
#include "preprocess/joint_network.h"
#include "common/mesh_file.h"
#include "common/scene.h"
#include "preprocess/scene_geometry.h"
#include "common/stopwatch.h"

namespace {

std::string scene_text(int joints, double h) {
  const double p21 = 0.5 * joints * 8.0 / 40000.0;
  auto set = [&](double mean_deg, double termination, int seed) {
    return nlohmann::json{
        {"friction_deg", 30},
        {"normal", {{"model", "constant"}, {"kn", 1e11}}},
        {"shear", {{"model", "constant"}, {"ks", 4e10}}},
        {"generate",
         {{"orientation", {{"mean_deg", mean_deg}, {"kappa", 10}}},
          {"p21", p21},
          {"length", {{"distribution", "exponential"}, {"mean", 8}}},
          {"termination", termination},
          {"seed", seed}}}};
  };
  nlohmann::json doc = {
      {"name", "dfn-bench"},
      {"materials", {{"rock", {{"density", 2650}, {"young", 1e10}, {"poisson", 0.25}}}}},
      {"bodies", {{{"material", "rock"}, {"outer", {{0, 0}, {200, 0}, {200, 200}, {0, 200}}}}}},
      {"mesh", {{"size", h}}},
      {"solver", {{"time_step", 1e-3}, {"steps", 1}}}};
  doc["joint_sets"] = nlohmann::json::object();
  if (joints > 0) {
    doc["joint_sets"]["a"] = set(30, 0, 1);
    doc["joint_sets"]["b"] = set(120, 0.5, 2);
  }
  return doc.dump();
}

struct Row {
  long joints = 0, triangles = 0, elements = 0, covers = 0, blocks = 0;
  double generation = 0, checks = 0, cutting = 0, writing = 0;
  nmm::pre::CutTimings cut;  ///< s, the cutting's phases
};

Row run_case(int target, double h, const std::string& mesh_path) {
  Row r;
  const std::string text = scene_text(target, h);
  nmm::Stopwatch t;
  nmm::SceneDef scene = nmm::parse_scene(text, "bench");
  const nlohmann::json doc = nmm::parse_json_text(text, "bench");
  const nlohmann::json expanded = nmm::pre::explicit_scene(doc, scene);
  const std::string explicit_text = expanded.dump(1) + "\n";
  scene = nmm::scene_from_json(expanded, "bench (generated joints)");
  r.generation = t.seconds();
  r.joints = static_cast<long>(scene.joints.size());
  t.restart();
  nmm::pre::check_scene_geometry(scene, "bench");
  r.checks = t.seconds();
  t.restart();
  nmm::Mesh mesh = nmm::pre::build_mesh(scene, "bench", &r.cut);
  r.cutting = t.seconds();
  mesh.scene_file = "bench";
  mesh.scene_text = explicit_text;
  mesh.scene_sha256 = nmm::sha256(explicit_text);
  t.restart();
  nmm::write_mesh_file(mesh, mesh_path);
  r.writing = t.seconds();
  r.triangles = static_cast<long>(mesh.triangle_count());
  r.elements = static_cast<long>(mesh.element_count());
  r.covers = static_cast<long>(mesh.cover_count());
  r.blocks = static_cast<long>(mesh.block_count());
  std::remove(mesh_path.c_str());
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  int max_joints = 20000;
  std::string csv_path = "dfn_bench.csv";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) quick = true;
    else if (!std::strcmp(argv[i], "--max-joints") && i + 1 < argc) max_joints = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv_path = argv[++i];
    else {
      std::fprintf(stderr, "usage: dfn_bench [--quick] [--max-joints N] [--csv FILE]\n");
      return 2;
    }
  }
  const double h = quick ? 4.0 : 1.0;
  std::vector<int> targets = {0, 625, 1250, 2500, 5000, 10000, 20000};
  if (quick) targets = {0, 200, 400};
  std::ofstream csv(csv_path);
  csv << "target_joints,joints,mesh_size_m,triangles,elements,physical_covers,blocks,"
         "generation_s,checks_s,cutting_s,arrangement_s,labelling_s,covers_s,writing_s,total_s,"
         "cpu_s,peak_rss_mb\n";
  std::printf("%8s %8s %9s %9s %8s %8s %8s %8s %8s %8s %8s\n", "target", "joints", "elements",
              "blocks", "gen_s", "check_s", "cut_s", "write_s", "total_s", "cpu_s", "rss_MB");
  for (int target : targets) {
    if (target > max_joints) break;
    int fd[2];
    if (pipe(fd) != 0) return 1;
    const pid_t pid = fork();
    if (pid == 0) {
      close(fd[0]);
      const Row r = run_case(target, h, "/tmp/dfn_bench_" + std::to_string(getpid()) + ".nmm");
      if (write(fd[1], &r, sizeof r) != static_cast<ssize_t>(sizeof r)) _exit(1);
      _exit(0);
    }
    close(fd[1]);
    Row r;
    const bool got = read(fd[0], &r, sizeof r) == static_cast<ssize_t>(sizeof r);
    close(fd[0]);
    int status = 0;
    struct rusage usage {};
    wait4(pid, &status, 0, &usage);
    if (!got || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      std::fprintf(stderr, "dfn_bench: case %d failed\n", target);
      return 1;
    }
    const double total = r.generation + r.checks + r.cutting + r.writing;
    const double rss_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: KiB
    // CPU seconds of the child (user + system): on a shared machine wall time includes waiting.
    const double cpu = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                       1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    char line[512];
    std::snprintf(line, sizeof line, "%d,%ld,%g,%ld,%ld,%ld,%ld,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.1f\n",
                  target, r.joints, h, r.triangles, r.elements, r.covers, r.blocks, r.generation,
                  r.checks, r.cutting, r.cut.arrangement, r.cut.labelling, r.cut.covers, r.writing,
                  total, cpu, rss_mb);
    csv << line << std::flush;
    std::printf("%8d %8ld %9ld %9ld %8.3f %8.3f %8.3f %8.3f %8.3f %8.3f %8.1f\n", target, r.joints,
                r.elements, r.blocks, r.generation, r.checks, r.cutting, r.writing, total, cpu,
                rss_mb);
    std::fflush(stdout);
  }
  return 0;
}
