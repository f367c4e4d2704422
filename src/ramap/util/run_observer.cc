#include "ramap/util/run_observer.h"

#include <chrono>

namespace ramap {

namespace {

thread_local RunObserver* current_observer = nullptr;
// When the owner thread last asked its observer (a thread asks only its own observer).
thread_local std::chrono::steady_clock::time_point last_asked;

}  // namespace

ScopedRunObserver::ScopedRunObserver(RunObserver* observer, bool owner)
    : previous_(current_observer) {
  if (observer != nullptr && owner) observer->owner_ = std::this_thread::get_id();
  current_observer = observer;
}

ScopedRunObserver::~ScopedRunObserver() { current_observer = previous_; }

RunObserver* CurrentRunObserver() { return current_observer; }

void CheckForStop() {
  RunObserver* observer = current_observer;
  if (observer == nullptr) return;
  if (!observer->stopped_ && observer->owner_ == std::this_thread::get_id()) {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_asked >= std::chrono::milliseconds(50)) {
      last_asked = now;
      if (observer->StopRequested()) observer->stopped_ = true;
    }
  }
  if (observer->stopped_) throw RunStopped();
}

void ReportStage(const std::string& stage, double seconds, const std::string& message) {
  if (current_observer != nullptr) current_observer->OnStage(stage, seconds, message);
  CheckForStop();
}

}  // namespace ramap
