// Threads of the dense kernels inside CHOLMOD's factorisation: OpenBLAS (pthreads) and OpenMP.
//
// Debian's CHOLMOD and OpenBLAS start a thread per core in every factorisation. For the systems
// of a block model (up to ~1e5 unknowns) the supernodes are small and those threads mostly wait
// and spin: on a 2-core machine whole runs were 1.7–2.2× slower than with one thread (11.1 vs
// 5.7 ms per factorisation of a 10 × 10 brick wall, 89k context switches in 30 steps). So the
// default is one thread below kThreadedUnknowns unknowns and all cores above, where the dense
// fronts are large enough to share (`nmm-solve --threads N` overrides; 0 = this default).
// Asking for one thread takes more than omp_set_num_threads with this CHOLMOD: its own thread
// count clause and libgomp's per-region overhead (solver_threads.cpp, docs/contact.md "Threads").
#pragma once

namespace nmm::solve {

/// Unknowns from which the default uses every core.
inline constexpr int kThreadedUnknowns = 150000;

/// The thread count the default picks for a system of `unknowns`.
int default_solver_threads(int unknowns);

/// Sets OpenBLAS's and OpenMP's thread counts (each only if the library is loaded; a reference
/// BLAS has no threads to set), also for OpenMP regions that name their own count (CHOLMOD's).
/// Returns the count set.
int set_solver_threads(int threads);

/// This thread was set to one solver thread: OpenMP regions of the libraries run as plain calls
/// (solver_threads.cpp, GOMP_parallel).
bool solver_runs_serial();

}  // namespace nmm::solve
