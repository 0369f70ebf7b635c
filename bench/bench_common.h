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

namespace nmm::bench {

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

}  // namespace nmm::bench
