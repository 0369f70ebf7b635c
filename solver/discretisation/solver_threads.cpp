#include "solver/discretisation/solver_threads.h"

#include <dlfcn.h>

#include <thread>

#include "solver/discretisation/loaded_symbol.h"

namespace nmm::solve {
namespace {
// The count set_solver_threads() set on this thread (0: never set, libgomp decides).
thread_local int solver_threads = 0;
}  // namespace

bool solver_runs_serial() { return solver_threads == 1; }

int default_solver_threads(int unknowns) {
  if (unknowns < kThreadedUnknowns) return 1;
  const unsigned cores = std::thread::hardware_concurrency();
  return cores > 0 ? static_cast<int>(cores) : 1;
}

int set_solver_threads(int threads) {
  if (threads < 1) threads = 1;
  solver_threads = threads;
  // Looked up at run time: the functions exist only when OpenBLAS / libgomp are the libraries
  // loaded behind CHOLMOD, and linking them by name would tie the build to one BLAS
  // (loaded_symbol.h: also where the Python module keeps them local).
  using SetThreads = void (*)(int);
  if (auto f = reinterpret_cast<SetThreads>(loaded_symbol("openblas_set_num_threads"))) f(threads);
  if (auto f = reinterpret_cast<SetThreads>(loaded_symbol("omp_set_num_threads"))) f(threads);
  // CHOLMOD's supernodal factorisation opens its parallel loops with a fixed
  // num_threads(CHOLMOD_OMP_NUM_THREADS) clause (4 in Debian's build), which overrides
  // omp_set_num_threads: one thread asked for still ran 4 OpenMP threads in every factorisation,
  // waiting on each other on 2 cores (20 × 20 brick wall, 15 steps: 9.0 s CPU, 2.6 s of it in
  // the kernel, against 4.8 s). One thread: no active parallel level at all (and the regions'
  // bodies are called directly, GOMP_parallel below). More: dynamic adjustment, under which
  // libgomp caps a clause's count at the count set above.
  using SetInt = void (*)(int);
  if (auto f = reinterpret_cast<SetInt>(loaded_symbol("omp_set_max_active_levels"))) f(threads > 1 ? 1 : 0);
  if (auto f = reinterpret_cast<SetInt>(loaded_symbol("omp_set_dynamic"))) f(threads > 1 ? 1 : 0);
  return threads;
}

}  // namespace nmm::solve

// CHOLMOD's supernodal factorisation opens an OpenMP parallel loop per supernode (thousands per
// factorisation). Even with one thread, libgomp sets up a team for each and ends it with a futex
// wake-up, a system call: on this virtual machine 15–18 % of a brick wall's step. CHOLMOD uses
// OpenMP only through GOMP_parallel, omp_get_num_threads and omp_get_thread_num (static loop
// schedules: `objdump -T libcholmod.so.3`), so on a thread set to one solver thread the region's
// body can simply be called: outside a team those two report 1 and 0, and the body runs the whole
// loop. Defined in the program, this GOMP_parallel is the one CHOLMOD's reference binds to; any
// other thread, or a count above one, goes on to libgomp's.
extern "C" void GOMP_parallel(void (*fn)(void*), void* data, unsigned num_threads, unsigned flags) {
  if (nmm::solve::solver_runs_serial()) {
    fn(data);
    return;
  }
  using Real = void (*)(void (*)(void*), void*, unsigned, unsigned);
  static const Real real = reinterpret_cast<Real>(dlsym(RTLD_NEXT, "GOMP_parallel"));
  if (real) real(fn, data, num_threads, flags);
  else fn(data);  // no libgomp behind the caller: there is no team to make
}
