// How much memory the process has needed: what scaling benchmarks and summary.json report.
#pragma once

namespace ramap {

// The peak resident set size of this process so far, in MiB (getrusage's ru_maxrss).
double PeakResidentMebibytes();

}  // namespace ramap
