#include "ramap/util/memory.h"

#include <sys/resource.h>

namespace ramap {

double PeakResidentMebibytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
  return usage.ru_maxrss / 1024.0;  // kibibytes on Linux
}

}  // namespace ramap
