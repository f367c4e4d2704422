#include "ramap/util/progress_line.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <utility>

namespace ramap {

bool IsTerminal(const std::ostream* out) {
  if (out == &std::cout) return ::isatty(STDOUT_FILENO) == 1;
  if (out == &std::cerr) return ::isatty(STDERR_FILENO) == 1;
  return false;
}

ProgressLine::ProgressLine(std::ostream* out, std::string what, size_t total, std::string unit)
    : ProgressLine(out, std::move(what), total, std::move(unit), IsTerminal(out)) {}

ProgressLine::ProgressLine(std::ostream* out, std::string what, size_t total, std::string unit,
                           bool terminal)
    : out_(out),
      what_(std::move(what)),
      total_(total),
      unit_(std::move(unit)),
      terminal_(terminal),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

std::string ProgressLine::Rate(size_t done, double seconds) const {
  char text[64];
  const double rate = seconds > 0 ? done / seconds : 0.0;
  std::snprintf(text, sizeof(text), rate >= 10 ? "%.0f/s" : "%.1f/s", rate);
  return text;
}

void ProgressLine::Update(size_t done) {
  if (out_ == nullptr || !terminal_ || finished_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_draw_ < std::chrono::milliseconds(250)) return;
  last_draw_ = now;
  const double seconds = std::chrono::duration<double>(now - start_).count();
  char left[48] = "";
  if (done > 0 && done < total_ && !total_is_a_limit_) {
    std::snprintf(left, sizeof(left), ", %.0f s left",
                  std::ceil(seconds * static_cast<double>(total_ - done) / done));
  }
  *out_ << "\r\033[K[ramap] " << what_ << ": " << done
        << (total_is_a_limit_ ? " of at most " : " / ") << total_ << " " << unit_ << ", "
        << Rate(done, seconds) << left << std::flush;
}

void ProgressLine::Finish(size_t done, bool completed) {
  if (out_ == nullptr || finished_) return;
  finished_ = true;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  char time[32];
  std::snprintf(time, sizeof(time), "%.1f s", seconds);
  if (terminal_) *out_ << "\r\033[K";
  *out_ << "[ramap] " << what_ << ": ";
  if (completed) {
    *out_ << done << " " << unit_ << " in " << time << " (" << Rate(done, seconds) << ")\n";
  } else {
    *out_ << "stopped at " << done << " of " << total_ << " " << unit_ << " after " << time << "\n";
  }
  *out_ << std::flush;
}

}  // namespace ramap
