// RunObserver: installed per thread, told of each stage, asked to stop at most every 50 ms by its
// own thread only, and a stop seen by every thread that shares it.
#include "ramap/util/run_observer.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

namespace ramap {
namespace {

class RecordingObserver : public RunObserver {
 public:
  void OnStage(const std::string& stage, double seconds, const std::string& message) override {
    stages.push_back(stage + " " + std::to_string(seconds) + " " + message);
  }
  bool StopRequested() override {
    ++num_asked;
    return stop;
  }
  std::vector<std::string> stages;
  std::atomic<int> num_asked{0};
  std::atomic<bool> stop{false};
};

// Runs `body` in a thread of its own: when an observer was last asked is the thread's, and a new
// thread has never asked.
template <typename Body>
void InFreshThread(Body body) {
  std::thread thread(body);
  thread.join();
}

TEST(RunObserver, InstalledWhileInScopeAndThePreviousOneRestored) {
  InFreshThread([] {
    EXPECT_EQ(CurrentRunObserver(), nullptr);
    RecordingObserver outer, inner;
    {
      ScopedRunObserver install_outer(&outer);
      EXPECT_EQ(CurrentRunObserver(), &outer);
      {
        ScopedRunObserver install_inner(&inner);
        EXPECT_EQ(CurrentRunObserver(), &inner);
        {
          ScopedRunObserver none(nullptr);
          EXPECT_EQ(CurrentRunObserver(), nullptr);
        }
        EXPECT_EQ(CurrentRunObserver(), &inner);
      }
      EXPECT_EQ(CurrentRunObserver(), &outer);
      // Another thread has none of its own.
      InFreshThread([] { EXPECT_EQ(CurrentRunObserver(), nullptr); });
    }
    EXPECT_EQ(CurrentRunObserver(), nullptr);
  });
}

TEST(RunObserver, WithoutAnObserverStagesAndChecksDoNothing) {
  InFreshThread([] {
    EXPECT_NO_THROW(ReportStage("rotation averaging", 1.0, "ok"));
    EXPECT_NO_THROW(CheckForStop());
  });
}

TEST(RunObserver, ReportStageTellsTheObserverEachStage) {
  InFreshThread([] {
    RecordingObserver observer;
    ScopedRunObserver install(&observer);
    ReportStage("relative poses", 0.5, "120 pairs");
    ReportStage("rotation averaging", 2.0, "certified");
    EXPECT_EQ(observer.stages, (std::vector<std::string>{"relative poses 0.500000 120 pairs",
                                                         "rotation averaging 2.000000 certified"}));
  });
}

TEST(RunObserver, StopRequestedEndsTheRunAtTheNextCheck) {
  InFreshThread([] {
    RecordingObserver observer;
    observer.stop = true;
    ScopedRunObserver install(&observer);
    EXPECT_THROW(CheckForStop(), RunStopped);  // a new thread asks at its first check
    EXPECT_EQ(observer.num_asked, 1);
    // Stopped stays stopped, without asking again; a stage's report checks too.
    EXPECT_THROW(CheckForStop(), RunStopped);
    EXPECT_THROW(ReportStage("stage", 1.0, ""), RunStopped);
    EXPECT_EQ(observer.num_asked, 1);
    EXPECT_EQ(observer.stages.size(), 1u);  // told of the stage before the stop was seen
  });
}

TEST(RunObserver, AskedAtMostEvery50Milliseconds) {
  InFreshThread([] {
    RecordingObserver observer;
    ScopedRunObserver install(&observer);
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < 1000; ++k) CheckForStop();
    const double elapsed_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    // Once at the first check, then once per 50 ms that passed (a slow machine may take a while).
    EXPECT_GE(observer.num_asked, 1);
    EXPECT_LE(observer.num_asked, 1 + static_cast<int>(elapsed_ms / 50.0));
    // 60 ms later (more than 50) the next check asks again.
    const int asked = observer.num_asked;
    std::this_thread::sleep_for(std::chrono::milliseconds(60));
    CheckForStop();
    EXPECT_EQ(observer.num_asked, asked + 1);
  });
}

TEST(RunObserver, WorkerThreadsNeverAskButSeeTheOwnersStop) {
  InFreshThread([] {
    RecordingObserver observer;
    observer.stop = true;
    ScopedRunObserver install(&observer);
    // A worker (owner false) does not ask, however long since the last ask: no stop yet.
    InFreshThread([&observer] {
      ScopedRunObserver worker(&observer, /*owner=*/false);
      EXPECT_NO_THROW(CheckForStop());
    });
    EXPECT_EQ(observer.num_asked, 0);
    // The owner asks and stops; the worker then sees the stop.
    EXPECT_THROW(CheckForStop(), RunStopped);
    InFreshThread([&observer] {
      ScopedRunObserver worker(&observer, /*owner=*/false);
      EXPECT_THROW(CheckForStop(), RunStopped);
    });
    EXPECT_EQ(observer.num_asked, 1);
  });
}

}  // namespace
}  // namespace ramap
