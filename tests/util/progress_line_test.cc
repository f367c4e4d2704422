// The progress line: redrawn in place on a terminal, one closing line elsewhere.
#include "ramap/util/progress_line.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "ramap/util/parallel.h"

namespace ramap {
namespace {

TEST(ProgressLine, PipedOutputGetsOneClosingLine) {
  std::ostringstream out;
  ProgressLine line(&out, "relative poses", 40, "pairs", /*terminal=*/false);
  for (size_t k = 1; k <= 40; ++k) line.Update(k);
  line.Finish(40, true);
  const std::string text = out.str();
  EXPECT_EQ(text.rfind("[ramap] relative poses: 40 pairs in ", 0), 0u) << text;
  EXPECT_NE(text.find("/s)\n"), std::string::npos) << text;
  EXPECT_EQ(text.find('\r'), std::string::npos) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
}

TEST(ProgressLine, TerminalRedrawsDoneTotalRateAndTimeLeft) {
  std::ostringstream out;
  ProgressLine line(&out, "matching", 100, "pairs", /*terminal=*/true);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  line.Update(25);
  const std::string drawn = out.str();
  EXPECT_EQ(drawn.rfind("\r\033[K[ramap] matching: 25 / 100 pairs, ", 0), 0u) << drawn;
  EXPECT_NE(drawn.find("/s, "), std::string::npos) << drawn;
  EXPECT_NE(drawn.find(" s left"), std::string::npos) << drawn;
  EXPECT_EQ(drawn.find('\n'), std::string::npos) << "no new line until the stage ends";
  line.Update(26);  // within 250 ms of the last drawing: not drawn again
  EXPECT_EQ(out.str(), drawn);
  line.Finish(100, true);
  EXPECT_NE(out.str().find("[ramap] matching: 100 pairs in "), std::string::npos) << out.str();
}

TEST(ProgressLine, AnIterationLimitIsNoPromiseOfTimeLeft) {
  std::ostringstream out;
  ProgressLine line(&out, "bundle adjustment", 200, "iterations", /*terminal=*/true);
  line.SetTotalIsALimit();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  line.Update(3);
  EXPECT_NE(out.str().find("3 of at most 200 iterations, "), std::string::npos) << out.str();
  EXPECT_EQ(out.str().find("left"), std::string::npos) << out.str();
  line.Finish(5, true);
  EXPECT_NE(out.str().find("[ramap] bundle adjustment: 5 iterations in "), std::string::npos)
      << out.str();
}

TEST(ProgressLine, AStoppedStageSaysWhereItStopped) {
  std::ostringstream out;
  ProgressLine line(&out, "bundle adjustment", 50, "iterations", /*terminal=*/false);
  line.Finish(7, false);
  EXPECT_NE(out.str().find("stopped at 7 of 50 iterations"), std::string::npos) << out.str();
}

TEST(ProgressLine, ParallelForClosesItsLineEvenWhenAnItemFails) {
  std::ostringstream out;
  EXPECT_THROW(ParallelFor(
                   20, 2,
                   [](size_t k) {
                     if (k == 5) throw std::runtime_error("item 5");
                   },
                   &out, "relative poses", "pairs"),
               std::runtime_error);
  EXPECT_NE(out.str().find("[ramap] relative poses: stopped at "), std::string::npos) << out.str();
}

}  // namespace
}  // namespace ramap
