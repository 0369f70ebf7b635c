// A function of a loaded library by name: see loaded_symbol.h.
#include "solver/discretisation/loaded_symbol.h"

#include <dlfcn.h>

namespace nmm::solve {

void* loaded_symbol(const char* name) {
  if (void* f = dlsym(RTLD_DEFAULT, name)) return f;
  // The shared object holding this function, opened again (RTLD_NOLOAD: only if it is loaded,
  // which it is) for a handle whose lookups search it and its dependencies.
  static void* const own = [] {
    Dl_info info{};
    return dladdr(reinterpret_cast<void*>(&loaded_symbol), &info) && info.dli_fname
               ? dlopen(info.dli_fname, RTLD_LAZY | RTLD_NOLOAD)
               : nullptr;
  }();
  return own ? dlsym(own, name) : nullptr;
}

}  // namespace nmm::solve
