// fuzz_cli: seeded mutation fuzzing of the tools' readers through their command lines
// (docs/fuzzing.md).
//
// Four campaigns, each a number of cases drawn from one seed (same seed, same cases):
//   scenes      mutate a valid scene (data/ and test scenes) and run nmm-preprocess on it;
//   sets        run nmm-solve on a small mesh with one mutated --set PATH=VALUE;
//   meshes      corrupt a valid mesh file (bit flips, truncation, overwrites, appended bytes)
//               and run nmm-inspect --json and nmm-solve on it;
//   checkpoints corrupt a checkpoint written by nmm-solve and run nmm-solve --restart on it
//               (skipped, and said so, when the solver writes no checkpoint).
// Every run must end with a permitted exit status (0 or 2; 3 too for the solver, a run that
// cannot go on), never by a signal, with exactly one line on stderr for status 2 and no output
// file left under the final name. A run still going after --timeout seconds is killed and
// counted as a time-out (reported; a failure only with --fail-on-timeout).
//
// Mutations of a scene (1 to 3 per case): a number replaced by 0, −1, 1, ±1e308, 1e-308, 2^63,
// a huge integer, or a literal the JSON grammar refuses (NaN, Infinity, 1e400); any value
// replaced by a string, null, true, an empty array or an empty object; a key deleted, renamed
// or duplicated (textually, as JSON allows); an array element deleted or duplicated; a polygon
// collapsed to one point or onto a line; a joint moved far away; all coordinates scaled.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/scene.h"
#include "common/whole_file.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// ---- random choices (std::mt19937_64 is specified bit for bit; no std distributions) ----------
struct Rng {
  std::mt19937_64 engine;
  explicit Rng(std::uint64_t seed) : engine(seed) {}
  std::uint64_t below(std::uint64_t n) { return n == 0 ? 0 : engine() % n; }
  bool chance(double p) { return static_cast<double>(engine() >> 11) * 0x1.0p-53 < p; }
  template <class T>
  const T& pick(const std::vector<T>& v) { return v[below(v.size())]; }
};

// ---- running a tool ----------------------------------------------------------------------------
struct RunResult {
  bool signaled = false;
  int signal = 0;
  int status = -1;
  bool timed_out = false;
  std::string err;  // stderr
  double seconds = 0;
};

RunResult run_tool(const std::vector<std::string>& args, double timeout_s) {
  RunResult r;
  int pipefd[2];
  if (pipe(pipefd) != 0) {
    perror("pipe");
    std::exit(1);
  }
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    const int devnull = open("/dev/null", O_RDWR);
    dup2(devnull, 0);
    dup2(devnull, 1);
    dup2(pipefd[1], 2);
    close(pipefd[0]);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  close(pipefd[1]);
  fcntl(pipefd[0], F_SETFL, O_NONBLOCK);
  char buf[4096];
  int wstatus = 0;
  for (;;) {
    ssize_t n;
    while ((n = read(pipefd[0], buf, sizeof buf)) > 0) r.err.append(buf, static_cast<size_t>(n));
    const pid_t done = waitpid(pid, &wstatus, WNOHANG);
    if (done == pid) break;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (elapsed > timeout_s && !r.timed_out) {
      r.timed_out = true;
      kill(pid, SIGKILL);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ssize_t n;
  while ((n = read(pipefd[0], buf, sizeof buf)) > 0) r.err.append(buf, static_cast<size_t>(n));
  close(pipefd[0]);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (WIFSIGNALED(wstatus)) {
    r.signaled = !r.timed_out;
    r.signal = WTERMSIG(wstatus);
  } else {
    r.status = WEXITSTATUS(wstatus);
  }
  return r;
}

// ---- the verdict on one run --------------------------------------------------------------------
struct Tally {
  std::map<int, int> by_status;
  int cases = 0, crashes = 0, bad_messages = 0, left_files = 0, timeouts = 0;
  std::vector<std::string> failures;  // first few, to print
  int failed() const { return crashes + bad_messages + left_files; }
};

std::string one_line(const std::string& s) {
  std::string out = s.substr(0, 300);
  for (char& c : out)
    if (c == '\n') c = '|';
  return out;
}

/// Judges a run: `allowed` statuses; `output` must exist after 0 and not after 2 (empty: none).
void judge(Tally& t, const RunResult& r, const std::vector<int>& allowed, const std::string& output,
           const std::string& what) {
  ++t.cases;
  auto fail = [&](int& counter, const std::string& why) {
    ++counter;
    if (t.failures.size() < 12) t.failures.push_back(why + " — " + what);
  };
  if (r.timed_out) {
    ++t.timeouts;
    if (t.failures.size() < 12) t.failures.push_back("time-out (not a failure) — " + what);
    return;
  }
  if (r.signaled) return fail(t.crashes, "killed by signal " + std::to_string(r.signal));
  ++t.by_status[r.status];
  bool ok_status = false;
  for (int s : allowed) ok_status |= s == r.status;
  if (!ok_status)
    return fail(t.crashes, "exit status " + std::to_string(r.status) + ": " + one_line(r.err));
  if (r.status == 2) {
    const std::size_t newlines = static_cast<std::size_t>(std::count(r.err.begin(), r.err.end(), '\n'));
    if (newlines != 1 || r.err.size() < 10 || r.err.back() != '\n')
      return fail(t.bad_messages, "status 2 with " + std::to_string(newlines) +
                                      " stderr lines: " + one_line(r.err));
    if (!output.empty() && fs::exists(output))
      return fail(t.left_files, "status 2 left " + output + " behind");
  }
}

void report(const std::string& name, const Tally& t, double seconds) {
  std::cout << "fuzz " << name << ": " << t.cases << " runs in " << static_cast<int>(seconds)
            << " s; exit";
  for (const auto& [s, n] : t.by_status) std::cout << " " << s << ": " << n << ",";
  std::cout << " crashes: " << t.crashes << ", bad messages: " << t.bad_messages
            << ", files left: " << t.left_files << ", time-outs: " << t.timeouts << "\n";
  for (const std::string& f : t.failures) std::cout << "  " << f << "\n";
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

// ---- scene mutations ---------------------------------------------------------------------------
// Values that JSON cannot hold are written as marker strings and replaced in the text.
const std::vector<std::string> kRawLiterals = {"NaN", "-Infinity", "Infinity", "1e400", "-1e400"};

json number_replacement(Rng& rng) {
  static const std::vector<json> values = {
      0,      -1,      1,       1e308,  -1e308,       1e-308, -1e-308,  0.5,
      1e9,    -1e9,    1e15,    1e-15,  9223372036854775807LL, -9223372036854775807LL - 1,
      18446744073709551615ULL, 2147483648LL, 1e30, 3};
  if (rng.chance(0.15)) return "__RAW__" + rng.pick(kRawLiterals);
  return rng.pick(values);
}

json other_replacement(Rng& rng) {
  static const std::vector<json> values = {"text",          "",  nullptr, true,         false,
                                           json::array(),   json::object(), json::array({1}),
                                           json::array({json::array()}),     "0.5", "rock"};
  return rng.pick(values);
}

// Every location in the document, as a JSON pointer.
void collect(const json& v, const json::json_pointer& at, std::vector<json::json_pointer>& out) {
  out.push_back(at);
  if (v.is_object())
    for (auto it = v.begin(); it != v.end(); ++it) collect(*it, at / it.key(), out);
  else if (v.is_array())
    for (std::size_t i = 0; i < v.size(); ++i) collect(v[i], at / i, out);
}

// Arrays of [x, y] points (rings, polylines).
bool is_point_list(const json& v) {
  if (!v.is_array() || v.size() < 2) return false;
  for (const json& p : v)
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number()) return false;
  return true;
}

void shift_points(json& list, double dx, double dy) {
  for (json& p : list) {
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number()) continue;
    p[0] = p[0].get<double>() + dx;
    p[1] = p[1].get<double>() + dy;
  }
}

void scale_all(json& v, double f) {
  if (v.is_array() && v.size() == 2 && v[0].is_number() && v[1].is_number()) {
    v[0] = v[0].get<double>() * f;
    v[1] = v[1].get<double>() * f;
    return;
  }
  if (v.is_structured())
    for (json& c : v) scale_all(c, f);
}

/// Applies one mutation to `doc`; textual ones (duplicate keys) are returned as (marker, text)
/// replacements for the dumped document.
void mutate_once(json& doc, Rng& rng, std::vector<std::pair<std::string, std::string>>& text_edits) {
  std::vector<json::json_pointer> at;
  collect(doc, json::json_pointer(), at);
  const json::json_pointer p = at[rng.below(at.size())];
  json& v = doc[p];
  const int kind = static_cast<int>(rng.below(10));
  switch (kind) {
    case 0:
    case 1: {  // a number somewhere
      std::vector<json::json_pointer> numbers;
      for (const auto& q : at)
        if (doc[q].is_number()) numbers.push_back(q);
      if (!numbers.empty()) doc[numbers[rng.below(numbers.size())]] = number_replacement(rng);
      break;
    }
    case 2:  // any value by a value of another type
      if (!p.empty()) v = other_replacement(rng);
      break;
    case 3:  // delete a key or an array element
      if (!p.empty()) {
        json& parent = doc[p.parent_pointer()];
        if (parent.is_object())
          parent.erase(p.back());
        else
          parent.erase(static_cast<std::size_t>(std::stoul(p.back())));
      }
      break;
    case 4:  // rename a key (a misspelling)
      if (!p.empty() && doc[p.parent_pointer()].is_object()) {
        json& parent = doc[p.parent_pointer()];
        json moved = parent[p.back()];
        parent.erase(p.back());
        parent[p.back() + "x"] = moved;
      }
      break;
    case 5:  // duplicate a key, textually (JSON permits it; the last one wins or it is refused)
      if (v.is_object() && !v.empty()) {
        auto it = v.begin();
        std::advance(it, static_cast<long>(rng.below(v.size())));
        const std::string marker = "__DUP__" + std::to_string(rng.below(1000000));
        v[marker] = rng.chance(0.5) ? number_replacement(rng) : other_replacement(rng);
        text_edits.push_back({"\"" + marker + "\"", json(it.key()).dump()});
      }
      break;
    case 6:  // duplicate or empty an array
      if (v.is_array()) {
        if (rng.chance(0.5) && !v.empty())
          v.push_back(v[rng.below(v.size())]);
        else
          v = json::array();
      }
      break;
    case 7: {  // collapse a polygon or polyline
      std::vector<json::json_pointer> lists;
      for (const auto& q : at)
        if (is_point_list(doc[q])) lists.push_back(q);
      if (lists.empty()) break;
      json& list = doc[lists[rng.below(lists.size())]];
      if (rng.chance(0.5)) {
        for (json& pt : list) pt = list[0];  // all at one point
      } else {
        for (std::size_t i = 0; i < list.size(); ++i)  // all on one line
          list[i] = json::array({static_cast<double>(i), 2.0 * static_cast<double>(i)});
      }
      break;
    }
    case 8: {  // move a joint (or any point list) far away
      std::vector<json::json_pointer> lists;
      for (const auto& q : at)
        if (is_point_list(doc[q])) lists.push_back(q);
      if (lists.empty()) break;
      static const std::vector<double> far = {1e3, 1e6, 9.99e6, 1e7, 5e7, 1e12, -1e6};
      shift_points(doc[lists[rng.below(lists.size())]], rng.pick(far), rng.pick(far));
      break;
    }
    case 9: {  // scale every coordinate
      static const std::vector<double> factors = {0, 1e-9, 1e-3, 1e3, 1e6, -1};
      scale_all(doc, rng.pick(factors));
      break;
    }
  }
}

std::string mutated_scene_text(const json& original, Rng& rng) {
  json doc = original;
  std::vector<std::pair<std::string, std::string>> edits;
  const int n = 1 + static_cast<int>(rng.below(3));
  for (int i = 0; i < n; ++i) mutate_once(doc, rng, edits);
  std::string text = doc.dump();
  for (const auto& [from, to] : edits) {
    const std::size_t at = text.find(from);
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  for (const std::string& raw : kRawLiterals) {  // "__RAW__NaN" → NaN
    const std::string marker = "\"__RAW__" + raw + "\"";
    for (std::size_t at; (at = text.find(marker)) != std::string::npos;)
      text.replace(at, marker.size(), raw);
  }
  return text;
}

// ---- byte corruption ---------------------------------------------------------------------------
std::string corrupt_bytes(const std::string& good, Rng& rng) {
  std::string b = good;
  switch (rng.below(5)) {
    case 0: {  // 1 to 8 bit flips
      const int flips = 1 + static_cast<int>(rng.below(8));
      for (int i = 0; i < flips && !b.empty(); ++i)
        b[rng.below(b.size())] ^= static_cast<char>(1u << rng.below(8));
      break;
    }
    case 1:  // truncation
      b.resize(rng.below(b.size()));
      break;
    case 2: {  // overwrite a range with zeros, 0xFF or random bytes
      if (b.empty()) break;
      const std::size_t at = rng.below(b.size());
      const std::size_t len = std::min<std::size_t>(b.size() - at, 1 + rng.below(64));
      const int fill = static_cast<int>(rng.below(3));
      for (std::size_t i = at; i < at + len; ++i)
        b[i] = fill == 0 ? '\0' : fill == 1 ? '\xff' : static_cast<char>(rng.below(256));
      break;
    }
    case 3:  // bytes appended
      b += std::string(1 + rng.below(100), static_cast<char>(rng.below(256)));
      break;
    case 4:  // a header field (first 128 bytes: magic, version, counts, offsets) set to extremes
      if (b.size() >= 8) {
        const std::size_t at = rng.below(std::min<std::size_t>(b.size(), 128) - 7);
        const std::uint64_t v = rng.chance(0.5) ? ~0ull : (1ull << 62) + rng.below(1000);
        std::memcpy(&b[at], &v, 8);
      }
      break;
  }
  return b;
}

// ---- --set values ------------------------------------------------------------------------------
std::vector<std::string> scene_paths(const json& v, const std::string& at) {
  std::vector<std::string> out;
  if (!at.empty()) out.push_back(at);
  if (v.is_object())
    for (auto it = v.begin(); it != v.end(); ++it) {
      auto sub = scene_paths(*it, at.empty() ? it.key() : at + "." + it.key());
      out.insert(out.end(), sub.begin(), sub.end());
    }
  return out;
}

std::string set_value(Rng& rng) {
  static const std::vector<std::string> values = {
      "0", "-1", "1", "1e308", "-1e308", "1e-308", "NaN", "Infinity", "1e400", "null", "true",
      "\"text\"", "\"\"", "[]", "{}", "[1,2]", "[0,0]", "[1e308,1e308]", "9223372036854775807",
      "18446744073709551615", "0.5", "-0.5", "1e9", "2", "\"constant\"", "{\"model\":\"constant\"}",
      "[", "{", "\"unterminated", "1e-3", "[[0,0],[1,1]]", "[{\"point\":[1,1],\"force\":[0,1e308]}]",
      "{\"density\":1e308,\"young\":1e308,\"poisson\":0.49}"};
  return rng.pick(values);
}

// Solver keys whose valid large values mean a long run: held at a short one.
bool long_run_key(const std::string& path) {
  return path == "solver.steps" || path == "solver.output_every" || path == "solver";
}

struct Options {
  std::uint64_t seed = 1;
  int scene_cases = 200, set_cases = 60, mesh_cases = 60, checkpoint_cases = 30;
  double timeout = 30;
  bool fail_on_timeout = false;
  std::string preprocess, solve, inspect, work;
  std::vector<std::string> scenes;
};

int usage() {
  std::cerr << "usage: fuzz_cli --preprocess BIN --solve BIN --inspect BIN --work DIR [--seed N]\n"
               "  [--scenes N] [--sets N] [--meshes N] [--checkpoints N] [--timeout S]\n"
               "  [--fail-on-timeout] SCENE.json...\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) std::exit(usage());
      return argv[++i];
    };
    if (a == "--seed") o.seed = std::stoull(next());
    else if (a == "--scenes") o.scene_cases = std::stoi(next());
    else if (a == "--sets") o.set_cases = std::stoi(next());
    else if (a == "--meshes") o.mesh_cases = std::stoi(next());
    else if (a == "--checkpoints") o.checkpoint_cases = std::stoi(next());
    else if (a == "--timeout") o.timeout = std::stod(next());
    else if (a == "--fail-on-timeout") o.fail_on_timeout = true;
    else if (a == "--preprocess") o.preprocess = next();
    else if (a == "--solve") o.solve = next();
    else if (a == "--inspect") o.inspect = next();
    else if (a == "--work") o.work = next();
    else if (!a.empty() && a[0] == '-') return usage();
    else o.scenes.push_back(a);
  }
  if (o.preprocess.empty() || o.solve.empty() || o.inspect.empty() || o.work.empty() ||
      o.scenes.empty())
    return usage();
  fs::create_directories(o.work);
  Rng rng(o.seed);
  std::cout << "fuzz_cli: seed " << o.seed << ", " << o.scenes.size() << " seed scenes\n";

  std::vector<json> seeds;
  for (const std::string& s : o.scenes)
    seeds.push_back(nmm::parse_json_text(nmm::read_text_file(s), s));

  int failed = 0;
  int timeouts = 0;
  auto finish = [&](const std::string& name, const Tally& t,
                    std::chrono::steady_clock::time_point t0) {
    report(name, t, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    failed += t.failed();
    timeouts += t.timeouts;
  };

  // 1. Scenes through nmm-preprocess.
  {
    const auto t0 = std::chrono::steady_clock::now();
    Tally t;
    const std::string scene = o.work + "/scene.json", mesh = o.work + "/scene.nmm";
    int kept = 0;
    for (int c = 0; c < o.scene_cases; ++c) {
      const std::size_t which = rng.below(seeds.size());
      const std::string text = mutated_scene_text(seeds[which], rng);
      write_file(scene, text);
      fs::remove(mesh);
      const RunResult r = run_tool({o.preprocess, scene, "-o", mesh, "-q"}, o.timeout);
      judge(t, r, {0, 2}, mesh, "case " + std::to_string(c) + " from " + o.scenes[which]);
      if (r.status == 0 && !fs::exists(mesh)) {
        ++t.left_files;
        t.failures.push_back("status 0 without " + mesh + " — case " + std::to_string(c));
      }
      // Keep the scene of every failed or timed-out case to rerun by hand.
      if (static_cast<int>(t.failures.size()) > kept) {
        kept = static_cast<int>(t.failures.size());
        write_file(o.work + "/scene_case_" + std::to_string(c) + ".json", text);
      }
    }
    finish("scenes (nmm-preprocess)", t, t0);
  }

  // A small valid mesh for the solver campaigns: the first seed scene that preprocesses.
  const std::string base_mesh = o.work + "/base.nmm";
  std::string base_scene;
  for (const std::string& s : o.scenes) {
    const RunResult r = run_tool({o.preprocess, s, "-o", base_mesh, "-q"}, o.timeout);
    if (r.status == 0) {
      base_scene = s;
      break;
    }
  }
  if (base_scene.empty()) {
    std::cout << "no seed scene preprocesses: solver campaigns not run\n";
    return 1;
  }
  const json base_doc = nmm::parse_json_text(nmm::read_text_file(base_scene), base_scene);
  std::vector<std::string> paths = scene_paths(base_doc, "");
  for (const char* extra : {"solver.static_mode", "solver.no_such_key", "joint_sets.no_such_set.friction_deg",
                            "materials.no_such_material.young", "excavate", "supports",
                            "tractions", "insitu_stress", "mesh.size", "bodies"})
    paths.push_back(extra);
  const std::vector<std::string> short_run = {"--set", "solver.steps=3", "--set",
                                              "solver.output_every=1", "--quiet"};

  // 2. --set values on nmm-solve.
  {
    const auto t0 = std::chrono::steady_clock::now();
    Tally t;
    const std::string out = o.work + "/set_run";
    for (int c = 0; c < o.set_cases; ++c) {
      std::vector<std::string> args = {o.solve, base_mesh, "-o", out};
      args.insert(args.end(), short_run.begin(), short_run.end());
      const std::string path = rng.pick(paths);
      std::string value = set_value(rng);
      if (long_run_key(path) && (value == "1e9" || value == "9223372036854775807"))
        value = "4";
      const int form = static_cast<int>(rng.below(6));
      std::string arg = path + "=" + value;
      if (form == 0) arg = path;                  // no '='
      if (form == 1) arg = "=" + value;           // no path
      if (form == 2) arg = path + ".." + "x=" + value;  // empty path segment
      args.push_back("--set");
      args.push_back(arg);
      fs::remove_all(out);
      const RunResult r = run_tool(args, o.timeout);
      judge(t, r, {0, 2, 3}, "", "case " + std::to_string(c) + ": --set " + arg);
    }
    finish("--set values (nmm-solve)", t, t0);
  }

  // 3. Corrupted mesh files through nmm-inspect and nmm-solve.
  {
    const auto t0 = std::chrono::steady_clock::now();
    Tally t;
    const std::string good = read_file(base_mesh);
    const std::string bad = o.work + "/corrupt.nmm", out = o.work + "/mesh_run";
    for (int c = 0; c < o.mesh_cases; ++c) {
      write_file(bad, corrupt_bytes(good, rng));
      const std::string what = "case " + std::to_string(c);
      judge(t, run_tool({o.inspect, bad, "--json"}, o.timeout), {0, 2}, "", what + " inspect");
      std::vector<std::string> args = {o.solve, bad, "-o", out};
      args.insert(args.end(), short_run.begin(), short_run.end());
      fs::remove_all(out);
      judge(t, run_tool(args, o.timeout), {0, 2, 3}, "", what + " solve");
    }
    finish("mesh files (nmm-inspect, nmm-solve)", t, t0);
  }

  // 4. Corrupted checkpoints through nmm-solve --restart.
  {
    const auto t0 = std::chrono::steady_clock::now();
    Tally t;
    const std::string first = o.work + "/checkpoint_run";
    fs::remove_all(first);
    std::vector<std::string> args = {o.solve, base_mesh, "-o", first};
    args.insert(args.end(), short_run.begin(), short_run.end());
    run_tool(args, o.timeout);
    const std::string state = first + "/checkpoint.nmmstate";
    if (!fs::exists(state)) {
      std::cout << "fuzz checkpoints: skipped, nmm-solve wrote no " << state << "\n";
    } else {
      const std::string good = read_file(state);
      const std::string bad = o.work + "/corrupt.nmmstate", out = o.work + "/restart_run";
      for (int c = 0; c < o.checkpoint_cases; ++c) {
        write_file(bad, corrupt_bytes(good, rng));
        std::vector<std::string> restart = {o.solve, base_mesh, "--restart", bad, "-o", out};
        restart.insert(restart.end(), short_run.begin(), short_run.end());
        fs::remove_all(out);
        judge(t, run_tool(restart, o.timeout), {0, 2, 3}, "", "case " + std::to_string(c));
      }
      finish("checkpoints (nmm-solve --restart)", t, t0);
    }
  }

  const int bad = failed + (o.fail_on_timeout ? timeouts : 0);
  std::cout << (bad == 0 ? "fuzz_cli: no crash, every failure one line\n"
                         : "fuzz_cli: FAILED\n");
  return bad == 0 ? 0 : 1;
}
