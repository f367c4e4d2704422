// One stage's progress on long work (features, matching, relative poses, bundle adjustment). On a
// terminal, a line redrawn in place at most four times a second: "[ramap] relative poses: 1234 /
// 5000 pairs, 410/s, 9 s left". Elsewhere (a pipe, a log file), only the closing line, so that a
// log holds one plain line per stage: "[ramap] relative poses: 5000 pairs in 12.2 s (410/s)".
#pragma once

#include <chrono>
#include <cstddef>
#include <ostream>
#include <string>

namespace ramap {

// Whether `out` is std::cout or std::cerr and that stream goes to a terminal.
bool IsTerminal(const std::ostream* out);

class ProgressLine {
 public:
  // Nothing is written when `out` is nullptr. `terminal`: redraw in place (IsTerminal by default).
  ProgressLine(std::ostream* out, std::string what, size_t total, std::string unit);
  ProgressLine(std::ostream* out, std::string what, size_t total, std::string unit, bool terminal);
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // The total is a limit the work may stop well before (a solver's iteration limit): the line says
  // "N of at most T" and guesses no time left.
  void SetTotalIsALimit() { total_is_a_limit_ = true; }
  // `done` of the total are finished. From one thread only (streams are not thread-safe).
  void Update(size_t done);
  // The closing line: "N unit in S s (R/s)" when the work completed (for an upper bound such as
  // a solver's iteration limit, before the total), "stopped at N of T" otherwise.
  void Finish(size_t done, bool completed);

 private:
  std::string Rate(size_t done, double seconds) const;

  std::ostream* out_;
  std::string what_;
  size_t total_;
  std::string unit_;
  bool terminal_;
  bool total_is_a_limit_ = false;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace ramap
