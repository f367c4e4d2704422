// A caller's view into a long run: each stage as it ends, and a way to stop the run between two
// steps. The command line installs none (a signal ends the process there); the Python module
// installs one that calls a progress callback and turns Ctrl-C into a clean stop.
#pragma once

#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>

namespace ramap {

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  // A stage ended (the mapper's stage names, mapper/stage_log.h).
  virtual void OnStage(const std::string& /*stage*/, double /*seconds*/,
                       const std::string& /*message*/) {}
  // Asked only in the thread that installed the observer, at most every 50 ms; true stops the run.
  virtual bool StopRequested() { return false; }

 private:
  friend class ScopedRunObserver;
  friend void CheckForStop();
  std::atomic<bool> stopped_{false};
  std::thread::id owner_;
};

// The run was stopped at its observer's request; outputs under way are removed by their guards
// (util/staged_output.h) as the exception unwinds.
class RunStopped : public std::runtime_error {
 public:
  RunStopped() : std::runtime_error("stopped on request") {}
};

// Installs `observer` for the calling thread while it lives (nullptr: none). `owner` is false in
// the worker threads a loop starts for a run (util/parallel.h): they only see a stop, never ask.
class ScopedRunObserver {
 public:
  explicit ScopedRunObserver(RunObserver* observer, bool owner = true);
  ~ScopedRunObserver();
  ScopedRunObserver(const ScopedRunObserver&) = delete;
  ScopedRunObserver& operator=(const ScopedRunObserver&) = delete;

 private:
  RunObserver* previous_;
};

// The calling thread's observer, or nullptr.
RunObserver* CurrentRunObserver();

// Throws RunStopped when the current observer asked to stop (asking it first, when this is its
// thread and 50 ms have passed since it was last asked). Cheap enough for every work item.
void CheckForStop();

// Tells the current observer, if any, that a stage ended.
void ReportStage(const std::string& stage, double seconds, const std::string& message);

}  // namespace ramap
