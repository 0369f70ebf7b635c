// nmm-sweep: the incline sweep (data/sweeps/incline_friction.json) run locally through Snakemake
// and with in-process threads: one row per variant, the same numbers from both engines, and the
// physics the rows must show (block on a 30° incline: a = g (sin α − cos α tan φ)).
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "common/math_constants.h"
#include "common/png_copy.h"
#include "studies/sweep.h"

namespace fs = std::filesystem;

namespace {

int run(const std::string& cmd) {
  const int st = std::system(cmd.c_str());
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

using Row = std::map<std::string, std::string>;

std::vector<Row> read_csv(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::vector<std::string> head;
  std::vector<Row> rows;
  auto split = [](const std::string& l) {
    std::vector<std::string> out;
    std::string cur;
    bool quoted = false;
    for (char c : l) {
      if (c == '"') quoted = !quoted;
      else if (c == ',' && !quoted) {
        out.push_back(cur);
        cur.clear();
      } else cur += c;
    }
    out.push_back(cur);
    return out;
  };
  if (!std::getline(in, line)) return rows;
  head = split(line);
  while (std::getline(in, line)) {
    const auto f = split(line);
    Row r;
    for (std::size_t i = 0; i < head.size() && i < f.size(); ++i) r[head[i]] = f[i];
    rows.push_back(r);
  }
  return rows;
}

const std::string kSweep = std::string(NMM_SOURCE_DIR) + "/data/sweeps/incline_friction.json";

std::vector<Row> sweep(const std::string& name, const std::string& engine) {
  const fs::path out = fs::path(NMM_TEST_WORK) / name;
  fs::remove_all(out);
  fs::create_directories(out.parent_path());
  const int rc = run(std::string(NMM_SWEEP) + " " + kSweep + " -o " + out.string() +
                     " --workers 2 --set solver.steps=100 --engine " + engine + " 2> " + out.string() + ".log");
  EXPECT_EQ(rc, 0) << "see " << out.string() << ".log";
  // sweep.svg: a panel per (varied parameter, numeric output): 2 parameters (variant, friction
  // angle) × 7 outputs (5 numeric summary keys of the 6 — status is text — and ux, uy of the
  // one measure point).
  std::stringstream svg;
  svg << std::ifstream(out / "sweep.svg").rdbuf();
  std::size_t nested = 0, titles = 0;
  for (std::size_t at = svg.str().find("<svg "); at != std::string::npos; at = svg.str().find("<svg ", at + 1))
    ++nested;
  for (std::size_t at = svg.str().find(" against "); at != std::string::npos; at = svg.str().find(" against ", at + 1))
    ++titles;
  EXPECT_EQ(nested, 1u + 14u) << "the grid and its panels";
  EXPECT_EQ(titles, 14u);
  EXPECT_NE(svg.str().find(">ux of point 0 against friction_deg<"), std::string::npos);
  EXPECT_EQ(fs::exists(out / "sweep.png"), nmm::png_converter_available());
  return read_csv(out / "sweep.csv");
}

}  // namespace

TEST(Sweep, InclineFrictionThroughSnakemakeAndThreads) {
  if (run("snakemake --version > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "snakemake is not installed (.ci/setup installs it)";
  const std::vector<Row> snake = sweep("incline_snakemake", "snakemake");
  const std::vector<Row> threads = sweep("incline_threads", "threads");
  ASSERT_EQ(snake.size(), 6u);  // 2 contact models × 3 friction angles
  ASSERT_EQ(threads.size(), 6u);
  std::map<std::string, std::map<int, std::pair<double, double>>> u;  // model → φ → (ux, uy)
  for (std::size_t i = 0; i < 6; ++i) {
    const Row& r = snake[i];
    EXPECT_EQ(r.at("exit"), "0");
    EXPECT_EQ(r.at("run_status"), "ok");
    EXPECT_EQ(r.at("summary.steps_completed"), "100");
    // The engines run the same commands: the same numbers (to round-off: the sparse solver's
    // threaded BLAS does not sum in a fixed order, and the joint laws' Newton iteration, which
    // stops at 0.1 %, can take another path from there: 1 µm on millimetres).
    const double ux = std::stod(r.at("history.ux.p0")), tx = std::stod(threads[i].at("history.ux.p0"));
    EXPECT_NEAR(ux, tx, 1e-6);
    EXPECT_EQ(r.at("joint_sets.interface.friction_deg"), threads[i].at("joint_sets.interface.friction_deg"));
    u[r.at("variant")][std::stoi(r.at("joint_sets.interface.friction_deg"))] = {
        std::stod(r.at("history.ux.p0")), std::stod(r.at("history.uy.p0"))};
  }
  const double g = 9.81, a = nmm::kPi / 6;
  auto accel = [&](double phi) { return g * (std::sin(a) - std::cos(a) * std::tan(phi * nmm::kPi / 180)); };
  for (const std::string model : {"springs", "joint-laws"}) {
    ASSERT_EQ(u[model].size(), 3u) << model;
    // Slip relative to the held block (φ = 40°), which removes the base's own sag.
    auto slip = [&](int phi) {
      return std::hypot(u[model][phi].first - u[model][40].first, u[model][phi].second - u[model][40].second);
    };
    const double ratio = slip(10) / slip(20);
    std::printf("%s: slip(10°) = %.4f m, slip(20°) = %.4f m, ratio %.3f (a ratio %.3f)\n", model.c_str(),
                slip(10), slip(20), ratio, accel(10) / accel(20));
    EXPECT_NEAR(ratio, accel(10) / accel(20), 0.15 * accel(10) / accel(20)) << model;
    EXPECT_NEAR(slip(20), 0.5 * accel(20) * 0.1 * 0.1, 0.25 * 0.5 * accel(20) * 0.01) << model;
  }
}

TEST(Sweep, BadSweepFileIsExitTwo) {
  const fs::path dir = fs::path(NMM_TEST_WORK) / "bad_sweep";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "a.json") << R"({"mesh": "none.nmm"})";
  std::ofstream(dir / "b.json") << R"({"scene": "b.json", "product": {"x": 3}})";
  std::ofstream(dir / "c.json") << R"({"scene": "c.json", "frobnicate": 1})";
  for (const char* f : {"a.json", "b.json", "c.json"}) {
    const int rc = run(std::string(NMM_SWEEP) + " " + (dir / f).string() + " -o " + (dir / "out").string() +
                       " 2> " + (dir / "err.txt").string());
    EXPECT_EQ(rc, 2) << f;
    std::ifstream in(dir / "err.txt");
    std::string all((std::istreambuf_iterator<char>(in)), {});
    EXPECT_EQ(std::count(all.begin(), all.end(), '\n'), 1) << f << ": " << all;
    EXPECT_NE(all.find(f), std::string::npos) << all;
  }
}

// Expansion: list × product × preprocess product; a run with preprocess settings gets its own
// mesh made by nmm-preprocess --set, the others share the base mesh.
TEST(Sweep, ExpandsListTimesProductAndPreprocessesPerSeed) {
  const fs::path dir = fs::path(NMM_TEST_WORK) / "expand";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "scene.json") << "{}";
  std::ofstream(dir / "s.json") << R"({
    "scene": "scene.json", "set": ["solver.steps=5"],
    "variants": [ {"name": "a"}, {"name": "b", "set": ["x.y=1"], "preprocess_set": ["joint_sets.j.generate.density=2"]} ],
    "product": {"p": [1, 2], "q": ["u", "v"]},
    "preprocess_product": {"joint_sets.j.generate.seed": [7, 8]} })";
  const nmm::studies::Sweep s = nmm::studies::read_sweep((dir / "s.json").string());
  ASSERT_EQ(s.runs.size(), 2u * 4u * 2u);
  EXPECT_EQ(s.parameters, (std::vector<std::string>{"variant", "p", "q", "preprocess:joint_sets.j.generate.seed"}));
  const auto jobs = nmm::studies::sweep_jobs(s, "/root", "/base.nmm", "solve", "pre");
  ASSERT_EQ(jobs.size(), s.runs.size());
  // The last run: variant b, p = 2, q = v, seed 8.
  const auto& last = jobs.back();
  ASSERT_EQ(last.commands.size(), 2u);
  const std::vector<std::string> pre = {"pre", (dir / "scene.json").string(), "-o", "/root/runs/r0016/mesh.nmm",
                                        "--set", "joint_sets.j.generate.density=2",
                                        "--set", "joint_sets.j.generate.seed=8"};
  EXPECT_EQ(last.commands[0], pre);
  const std::vector<std::string> solve = {"solve", "/root/runs/r0016/mesh.nmm", "-o", "/root/runs/r0016/out",
                                          "--quiet", "--set", "solver.steps=5", "--set", "x.y=1",
                                          "--set", "p=2", "--set", "q=v"};
  EXPECT_EQ(last.commands[1], solve);
}
