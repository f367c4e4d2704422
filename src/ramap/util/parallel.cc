#include "ramap/util/parallel.h"

#include <atomic>
#include <thread>
#include <vector>

namespace ramap {

void ParallelFor(size_t count, int num_threads, const std::function<void(size_t)>& work,
                 std::ostream* progress, const std::string& what, const std::string& unit) {
  std::atomic<size_t> next{0};
  std::atomic<size_t> done{0};
  size_t reported = 0;  // tens of percent shown so far; touched by the calling thread only
  auto report = [&](size_t finished) {
    if (reported == 0) *progress << "[ramap] " << what << " of " << count << " " << unit << ":";
    reported = finished * 10 / count;
    *progress << " " << 10 * reported << "%" << std::flush;
  };
  auto run = [&](bool reporting) {
    for (size_t k = next++; k < count; k = next++) {
      work(k);
      const size_t finished = ++done;
      if (reporting && progress != nullptr && finished * 10 / count > reported) report(finished);
    }
  };
  std::vector<std::thread> threads;
  for (int t = 1; t < num_threads; ++t) threads.emplace_back(run, false);
  run(true);
  for (std::thread& thread : threads) thread.join();
  if (progress != nullptr && count > 0) {
    if (reported < 10) report(count);
    *progress << "\n" << std::flush;
  }
}

}  // namespace ramap
