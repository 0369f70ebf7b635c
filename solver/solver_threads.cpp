#include "solver_threads.h"

#include <dlfcn.h>

#include <thread>

namespace nmm::solve {

int default_solver_threads(int unknowns) {
  if (unknowns < kThreadedUnknowns) return 1;
  const unsigned cores = std::thread::hardware_concurrency();
  return cores > 0 ? static_cast<int>(cores) : 1;
}

int set_solver_threads(int threads) {
  if (threads < 1) threads = 1;
  // Looked up at run time: the functions exist only when OpenBLAS / libgomp are the libraries
  // loaded behind CHOLMOD, and linking them by name would tie the build to one BLAS.
  using SetThreads = void (*)(int);
  if (auto f = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) f(threads);
  if (auto f = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "omp_set_num_threads"))) f(threads);
  // CHOLMOD's supernodal factorisation opens its parallel loops with a fixed
  // num_threads(CHOLMOD_OMP_NUM_THREADS) clause (4 in Debian's build), which overrides
  // omp_set_num_threads: one thread asked for still ran 4 OpenMP threads in every factorisation,
  // waiting on each other on 2 cores (20 × 20 brick wall, 15 steps: 9.0 s CPU, 2.6 s of it in
  // the kernel, against 4.8 s). One thread: no active parallel level at all (libgomp then runs a
  // region on the calling thread without asking the system anything). More: dynamic adjustment,
  // under which libgomp caps a clause's count at the count set above.
  using SetInt = void (*)(int);
  if (auto f = reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"))) f(threads > 1 ? 1 : 0);
  if (auto f = reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, "omp_set_dynamic"))) f(threads > 1 ? 1 : 0);
  return threads;
}

}  // namespace nmm::solve
