// One solver thread is one thread (solver/discretisation/solver_threads.cpp, docs/contact.md "Threads"):
// Debian's CHOLMOD asks OpenMP for 4 threads in a clause of its own, which used to start 3 more
// threads in the first factorisation of a run that had asked for one.
#include <dlfcn.h>
#include <filesystem>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "solver/discretisation/solver_threads.h"
#include "solver/discretisation/system_matrix.h"

extern "C" void GOMP_parallel(void (*fn)(void*), void* data, unsigned num_threads, unsigned flags);

namespace {

std::size_t threads_of_this_process() {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator("/proc/self/task")) ++n;
  return n;
}

// A chain of n unknowns, K = tridiag(−1, 2 + 1e-3, −1): large enough (n > 128) for every
// OpenMP loop of CHOLMOD's supernodal factorisation to open a parallel region.
bool factorise_chain(int n) {
  std::vector<int> offsets{0}, dofs;
  for (int i = 0; i + 1 < n; ++i) {
    dofs.insert(dofs.end(), {i, i + 1});
    offsets.push_back(static_cast<int>(dofs.size()));
  }
  nmm::solve::SystemMatrix k;
  k.build_pattern(n, offsets, dofs);
  const double block[4] = {1, -1, -1, 1};  // column-major 2 × 2
  for (std::size_t g = 0; g + 1 < offsets.size(); ++g) k.add_group(g, block);
  for (int i = 0; i < n; ++i) k.add_diagonal(i, 1e-3 + (i == 0 || i == n - 1 ? 1 : 0));
  return k.factorize();
}

struct Probe {
  std::thread::id caller;
  int calls = 0;
  bool elsewhere = false;
};

void probe_body(void* p) {
  auto* probe = static_cast<Probe*>(p);
  ++probe->calls;  // one thread: no race
  probe->elsewhere |= std::this_thread::get_id() != probe->caller;
}

}  // namespace

TEST(SolverThreads, OneThreadFactorisesWithoutStartingThreads) {
  nmm::solve::set_solver_threads(1);
  const std::size_t before = threads_of_this_process();
  ASSERT_TRUE(factorise_chain(20000));
  ASSERT_TRUE(factorise_chain(20000));
  EXPECT_EQ(threads_of_this_process(), before) << "a one-thread factorisation started threads";
}

TEST(SolverThreads, CholmodsParallelRegionsRunAsPlainCallsOnOneThread) {
  // CHOLMOD's reference to GOMP_parallel binds to the program's definition (ours), not libgomp's.
  EXPECT_EQ(dlsym(RTLD_DEFAULT, "GOMP_parallel"), reinterpret_cast<void*>(&GOMP_parallel));
  nmm::solve::set_solver_threads(1);
  EXPECT_TRUE(nmm::solve::solver_runs_serial());
  Probe probe{std::this_thread::get_id()};
  GOMP_parallel(probe_body, &probe, 4, 0);  // as CHOLMOD's num_threads(4) clause calls it
  EXPECT_EQ(probe.calls, 1);
  EXPECT_FALSE(probe.elsewhere);
}
