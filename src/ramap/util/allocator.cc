#include "ramap/util/allocator.h"

#include <cstdlib>  // defines __GLIBC__ with the C library's version

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace ramap {

void KeepFreedMemoryForReuse() {
#if defined(__GLIBC__)
  // glibc's ceiling for its adaptive mmap threshold on 64-bit systems, and twice it for trimming,
  // the ratio glibc keeps between the two: memory stays bounded as with glibc's own adaptation.
  constexpr int kMmapThresholdBytes = 32 << 20;
  constexpr int kTrimThresholdBytes = 64 << 20;
  mallopt(M_MMAP_THRESHOLD, kMmapThresholdBytes);
  mallopt(M_TRIM_THRESHOLD, kTrimThresholdBytes);
#endif
}

}  // namespace ramap
