#include "ramap/util/blas_threads.h"

#include <dlfcn.h>

#include <algorithm>

namespace ramap {

// Looked up at run time: the binary links the generic libblas.so.3, which is OpenBLAS only when
// the alternatives point there, and ATLAS or the reference BLAS have no such functions.
bool LimitBlasThreads(int num_threads) {
  using SetThreads = void (*)(int);
  const auto set_threads =
      reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  if (set_threads == nullptr) return false;
  set_threads(std::max(1, num_threads));
  return true;
}

int BlasThreads() {
  using GetThreads = int (*)();
  const auto get_threads =
      reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  return get_threads == nullptr ? 0 : get_threads();
}

SingleBlasThread::SingleBlasThread() : previous_(BlasThreads()) {
  if (previous_ > 1) LimitBlasThreads(1);
}

SingleBlasThread::~SingleBlasThread() {
  if (previous_ > 1) LimitBlasThreads(previous_);
}

}  // namespace ramap
