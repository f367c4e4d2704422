#include "ramap/util/blas_threads.h"

#include <dlfcn.h>

#include <algorithm>

namespace ramap {

namespace {

// Looked up at run time: the binary links the generic libblas.so.3, which is OpenBLAS only when
// the alternatives point there, and ATLAS or the reference BLAS have no such functions. A Python
// extension's libraries are loaded privately (not in the global scope RTLD_DEFAULT searches), so
// libblas.so.3 is also asked by name.
void* BlasFunction(const char* name) {
  if (void* function = dlsym(RTLD_DEFAULT, name)) return function;
  static void* const library = dlopen("libblas.so.3", RTLD_LAZY | RTLD_NOLOAD);
  return library == nullptr ? nullptr : dlsym(library, name);
}

}  // namespace

bool LimitBlasThreads(int num_threads) {
  using SetThreads = void (*)(int);
  const auto set_threads = reinterpret_cast<SetThreads>(BlasFunction("openblas_set_num_threads"));
  if (set_threads == nullptr) return false;
  set_threads(std::max(1, num_threads));
  return true;
}

int BlasThreads() {
  using GetThreads = int (*)();
  const auto get_threads = reinterpret_cast<GetThreads>(BlasFunction("openblas_get_num_threads"));
  return get_threads == nullptr ? 0 : get_threads();
}

ScopedBlasThreads::ScopedBlasThreads(int num_threads) : previous_(BlasThreads()) {
  LimitBlasThreads(num_threads);
}

ScopedBlasThreads::~ScopedBlasThreads() {
  if (previous_ > 0) LimitBlasThreads(previous_);
}

}  // namespace ramap
