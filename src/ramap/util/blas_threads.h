// How many threads the BLAS under CHOLMOD may use.
#pragma once

namespace ramap {

// Limits the threads of the BLAS that the sparse factorisations' dense kernels run in, when it is
// OpenBLAS (Debian's alternatives choose libblas.so.3 at run time); any other BLAS is left as it
// is. Returns whether the limit was applied.
bool LimitBlasThreads(int num_threads);

// The BLAS's current thread limit; 0 when the BLAS is not OpenBLAS.
int BlasThreads();

// `num_threads` BLAS threads for as long as it lives, then the limit there was before: a run of the
// mapper sets its own and leaves the process (a Python interpreter, say) as it found it.
class ScopedBlasThreads {
 public:
  explicit ScopedBlasThreads(int num_threads);
  ~ScopedBlasThreads();
  ScopedBlasThreads(const ScopedBlasThreads&) = delete;
  ScopedBlasThreads& operator=(const ScopedBlasThreads&) = delete;

 private:
  int previous_ = 0;
};

// One BLAS thread for as long as it lives, then the limit there was before. For stages that
// factorise many small systems on several threads of their own: each factorisation is too small
// to share, and OpenBLAS's extra threads only spin (yielding) beside the busy ones. On a long
// drive this made the translation windows' solves much quicker (BENCHMARKS.md, "Scale").
class SingleBlasThread : public ScopedBlasThreads {
 public:
  SingleBlasThread() : ScopedBlasThreads(1) {}
};

}  // namespace ramap
