// Marks at the points of a run where its memory is worth reading: the phases of a new
// pattern's analysis and factorisation (system_matrix.cpp), the run's peak on the largest walls.
// Nothing happens unless a probe is set: a bench (contact_bench --trace --memory) sets one that
// reads the resident memory, its peak since the last mark and the heap's use at each mark, so
// that a peak can be put down to the phase it happened in and to what was live then
// (docs/performance.md (h)). A mark costs one test of a pointer without a probe.
#pragma once

#include <functional>
#include <utility>

namespace nmm {

/// Called at each mark with its name ("analysis", "factorisation", ...).
using MemoryProbe = std::function<void(const char* phase)>;

namespace detail {
inline MemoryProbe& memory_probe() {
  static MemoryProbe probe;
  return probe;
}
}  // namespace detail

/// Sets the probe (an empty one: none); one per process, set before a run, not thread-safe.
inline void set_memory_probe(MemoryProbe probe) { detail::memory_probe() = std::move(probe); }

/// The run has reached `phase`: the probe, if any, reads the memory there.
inline void memory_mark(const char* phase) {
  if (const MemoryProbe& probe = detail::memory_probe()) probe(phase);
}

}  // namespace nmm
