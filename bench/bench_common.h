// Small helpers the benchmarks share: size lists from the command line, the machine's load
// (recorded next to every timing, since the 2-core machine is often shared) and the calling
// thread's CPU time (which excludes the time other jobs take the core away).
#pragma once

#include <time.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/scene.h"

namespace nmm::bench {

/// A square body of rock (side m, corner at the origin; 2650 kg/m³, E 10 GPa, ν 0.25) with one
/// joint set "j" (φ 30°, kn 1e11 Pa/m, ks 4e10 Pa/m) and no joints yet, cut at mesh size h (m).
inline SceneDef square_rock(double side, double h) {
  SceneDef s;
  s.materials.push_back({"rock", 2650, 1e10, 0.25, {}});
  JointSetDef js;
  js.name = "j";
  js.friction_deg = 30;
  js.normal.kn = 1e11;
  js.shear.ks = 4e10;
  s.joint_sets.push_back(js);
  BodyDef b;
  b.material = 0;
  b.outer = {{0, 0}, {side, 0}, {side, side}, {0, side}};
  s.bodies.push_back(b);
  s.mesh_size = h;
  return s;
}

/// "10,20,30" → {10, 20, 30}.
inline std::vector<int> parse_sizes(const char* s) {
  std::vector<int> v;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) v.push_back(std::stoi(item));
  return v;
}

/// Opens the CSV at `path` and writes its header line there and on stdout (every bench echoes
/// its rows to the terminal as it writes them).
inline std::ofstream start_csv(const std::string& path, const char* header) {
  std::ofstream csv(path);
  csv << header;
  std::fputs(header, stdout);
  return csv;
}

/// The 1-minute load average (/proc/loadavg), −1 where it cannot be read.
inline double load_average() {
  std::ifstream f("/proc/loadavg");
  double l = -1;
  f >> l;
  return l;
}

/// s, CPU time of the calling thread.
inline double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// MB, this process's resident memory now (VmRSS) and at its peak so far (VmHWM), from
/// /proc/self/status; −1 where it cannot be read.
struct Resident {
  double now_mb = -1, peak_mb = -1;
};
inline Resident resident() {
  Resident r;
  std::ifstream f("/proc/self/status");
  std::string key;
  double kb = 0;
  while (f >> key) {
    if (key == "VmRSS:" && f >> kb) r.now_mb = kb / 1024;
    else if (key == "VmHWM:" && f >> kb) r.peak_mb = kb / 1024;
  }
  return r;
}

/// Starts the peak of resident() afresh from what is resident now (Linux: clear_refs 5).
inline void reset_peak_resident() { std::ofstream("/proc/self/clear_refs") << "5"; }

}  // namespace nmm::bench
