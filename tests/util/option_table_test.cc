// Options renamed keep their former names as aliases (README, "Renamed"): the command line,
// Python and the checks find a declaration by either name, and the options reference says so.
#include "ramap/util/option_table.h"

#include <gtest/gtest.h>

#include "test_support.h"

namespace ramap {
namespace {

struct WindowSettings {
  int keyframe_interval = 30;
};

OptionTable<WindowSettings> WindowTable() {
  return {FormerlyNamed(
      NumberOption<WindowSettings>(
          "ViewGraph.keyframe_interval", [](auto& s) -> auto& { return s.keyframe_interval; },
          AtLeast(1), "frames between keyframes"),
      "PoseGraph.keyframe_interval")};
}

TEST(OptionTable, AFormerNameSetsTheRenamedOption) {
  WindowSettings settings;
  SetOption(WindowTable(), "PoseGraph.keyframe_interval", "12", &settings);
  EXPECT_EQ(settings.keyframe_interval, 12);
  SetOption(WindowTable(), "ViewGraph.keyframe_interval", "7", &settings);
  EXPECT_EQ(settings.keyframe_interval, 7);
}

TEST(OptionTable, AFormerNameIsCheckedAndNamedAsTheOptionIsNow) {
  WindowSettings settings;
  test::ExpectInputError(
      [&] { SetOption(WindowTable(), "PoseGraph.keyframe_interval", "0", &settings); },
      {"--ViewGraph.keyframe_interval"});
  EXPECT_EQ(settings.keyframe_interval, 30);
}

TEST(OptionTable, UnknownNamesAreStillRefused) {
  WindowSettings settings;
  test::ExpectInputError(
      [&] { SetOption(WindowTable(), "PoseGraph.keyframe_intervals", "3", &settings); },
      {"no such option"});
}

TEST(OptionTable, TheReferenceNamesTheFormerName) {
  const std::string markdown = OptionTableMarkdown(WindowTable(), WindowSettings());
  EXPECT_NE(markdown.find("`--ViewGraph.keyframe_interval` | 30 |"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("(formerly `--PoseGraph.keyframe_interval`)"), std::string::npos)
      << markdown;
}

}  // namespace
}  // namespace ramap
