#include "ramap/util/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "ramap/util/progress_line.h"
#include "ramap/util/run_observer.h"

namespace ramap {

void ParallelFor(size_t count, int num_threads, const std::function<void(size_t)>& work,
                 std::ostream* progress, const std::string& what, const std::string& unit) {
  std::atomic<size_t> next{0};
  std::atomic<size_t> done{0};
  // The first exception of any work item; once set, every thread stops taking new items and the
  // caller rethrows it, so a failure inside a worker ends as the command's one error message
  // instead of std::terminate.
  std::exception_ptr first_error;
  std::mutex error_mutex;
  std::atomic<bool> failed{false};
  // Drawn by the calling thread only.
  ProgressLine line(progress, what, count, unit);
  // Workers see the caller's observer, so a stop asked for reaches every thread's next item.
  RunObserver* const observer = CurrentRunObserver();
  auto run = [&](bool reporting) {
    const ScopedRunObserver worker_observer(observer, /*owner=*/false);
    for (size_t k = next++; k < count && !failed; k = next++) {
      try {
        CheckForStop();
        work(k);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!first_error) first_error = std::current_exception();
        failed = true;
        return;
      }
      const size_t finished = ++done;
      if (reporting) line.Update(finished);
    }
  };
  std::vector<std::thread> threads;
  for (int t = 1; t < num_threads; ++t) threads.emplace_back(run, false);
  run(true);
  for (std::thread& thread : threads) thread.join();
  if (count > 0) line.Finish(done, done == count);
  if (first_error) std::rethrow_exception(first_error);
}

size_t NumShares(size_t count, int num_threads, size_t min_per_share) {
  const size_t most = count / std::max<size_t>(1, min_per_share);
  return std::max<size_t>(1, std::min<size_t>(std::max(1, num_threads), most));
}

void ForEachShare(size_t count, size_t num_shares,
                  const std::function<void(size_t share, size_t begin, size_t end)>& work) {
  num_shares = std::max<size_t>(1, num_shares);
  ParallelFor(num_shares, static_cast<int>(num_shares), [&](size_t share) {
    work(share, share * count / num_shares, (share + 1) * count / num_shares);
  });
}

}  // namespace ramap
