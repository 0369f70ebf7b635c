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
  return threads;
}

}  // namespace nmm::solve
