// Independent work items on a few threads, with one progress line (util/progress_line.h).
#pragma once

#include <cstddef>
#include <functional>
#include <ostream>
#include <string>

namespace ramap {

// Runs work(k) for k in [0, count) on `num_threads` threads (the calling thread among them).
// With `progress`, a ProgressLine of <what> and <unit> is written there by the calling thread
// only (streams are not thread-safe): redrawn in place on a terminal, the closing line alone
// elsewhere. The first exception
// thrown by any work item stops the loop (items under way finish) and is rethrown to the caller.
void ParallelFor(size_t count, int num_threads, const std::function<void(size_t)>& work,
                 std::ostream* progress = nullptr, const std::string& what = "",
                 const std::string& unit = "");

}  // namespace ramap
