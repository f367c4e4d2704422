#include "ramap/util/blas_threads.h"

#include <dlfcn.h>

#include <algorithm>

namespace ramap {

bool LimitBlasThreads(int num_threads) {
  // Looked up at run time: the binary links the generic libblas.so.3, which is OpenBLAS only when
  // the alternatives point there, and ATLAS or the reference BLAS have no such function.
  using SetThreads = void (*)(int);
  const auto set_threads =
      reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  if (set_threads == nullptr) return false;
  set_threads(std::max(1, num_threads));
  return true;
}

}  // namespace ramap
