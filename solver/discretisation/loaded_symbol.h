// A function of a library loaded behind the solver (OpenBLAS, libgomp), looked up by name at run
// time, so that the build is tied to no one BLAS (solver_threads.cpp, blas_info.cpp).
//
// A program (the tools) has those libraries in its global scope, where dlsym(RTLD_DEFAULT) finds
// them. A shared object loaded with its libraries kept local (the Python module: CPython loads
// extension modules with RTLD_LOCAL) has them only in its own scope: there the lookup goes on
// in the shared object that holds this code and its dependencies.
#pragma once

namespace nmm::solve {

/// The address of `name` in the global scope, else in this code's shared object and its
/// dependencies; null when no loaded library defines it.
void* loaded_symbol(const char* name);

}  // namespace nmm::solve
