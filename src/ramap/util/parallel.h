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

// How many fixed shares `count` items are split into: one per thread, none smaller than
// `min_per_share` (below that a thread costs more than it saves), and at least one.
size_t NumShares(size_t count, int num_threads, size_t min_per_share);

// Runs work(share, begin, end) for each of `num_shares` contiguous shares of [0, count), one
// thread each. The split depends on the counts alone, so sums taken per share and combined in
// share order come out the same whatever the timing.
void ForEachShare(size_t count, size_t num_shares,
                  const std::function<void(size_t share, size_t begin, size_t end)>& work);

}  // namespace ramap
