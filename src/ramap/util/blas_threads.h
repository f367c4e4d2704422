// How many threads the BLAS under CHOLMOD may use.
#pragma once

namespace ramap {

// Limits the threads of the BLAS that the sparse factorisations' dense kernels run in, when it is
// OpenBLAS (Debian's alternatives choose libblas.so.3 at run time); any other BLAS is left as it
// is. Returns whether the limit was applied.
bool LimitBlasThreads(int num_threads);

}  // namespace ramap
