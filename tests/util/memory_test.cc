// PeakResidentMebibytes: the process's peak resident set, as the kernel counts it, in MiB.
#include "ramap/util/memory.h"

#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <string>

namespace ramap {
namespace {

// The kernel's own peak resident set size (VmHWM) in MiB, or -1 when /proc is not there.
double VmHwmMebibytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // "N kB"
  }
  return -1.0;
}

TEST(Memory, PeakAgreesWithTheKernelsHighWaterMark) {
  const double before = VmHwmMebibytes();
  if (before < 0) GTEST_SKIP() << "no /proc/self/status on this system";
  const double peak = PeakResidentMebibytes();
  const double after = VmHwmMebibytes();
  // Both count the same pages, but the kernel folds each thread's cached RSS counts into the
  // process's lazily (64 events at a time), so the two readings may differ by some pages: 4 MiB
  // is far more than that and far less than the 64 MiB the next test moves the peak by.
  EXPECT_GE(peak, before - 4.0);
  EXPECT_LE(peak, after + 4.0);
}

TEST(Memory, PeakCoversMemoryTouchedNowAndNeverFalls) {
  const double first = PeakResidentMebibytes();
  constexpr size_t kMebibytes = 64;
  {
    const std::unique_ptr<char[]> block(new char[kMebibytes << 20]);
    // Resident only once written: one byte per page, through volatile so that it is written.
    volatile char* bytes = block.get();
    for (size_t k = 0; k < (kMebibytes << 20); k += 4096) bytes[k] = 1;
    EXPECT_GE(PeakResidentMebibytes(), static_cast<double>(kMebibytes));
  }
  // Freed memory leaves the peak where it was.
  EXPECT_GE(PeakResidentMebibytes(), first);
  EXPECT_GE(PeakResidentMebibytes(), static_cast<double>(kMebibytes));
}

}  // namespace
}  // namespace ramap
