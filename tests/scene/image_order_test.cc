#include "ramap/scene/image_order.h"

#include <gtest/gtest.h>

namespace ramap {
namespace {

TEST(ImageOrder, FrameNumbersSortNumerically) {
  const std::vector<std::string> names = {"img_10.png", "img_9.png", "img_100.png", "img_1.png"};
  EXPECT_EQ(CaptureOrder(names), (std::vector<size_t>{3, 1, 0, 2}));
  EXPECT_TRUE(LooksSequential(names));
}

TEST(ImageOrder, MixedPrefixesOrNamesWithoutNumbersAreUnordered) {
  EXPECT_FALSE(LooksSequential({"left_1.png", "right_1.png"}));
  EXPECT_FALSE(LooksSequential({"frame_1.png", "castle.jpg"}));
  const std::vector<std::string> names = {"b.jpg", "a.jpg", "a2.jpg"};
  EXPECT_EQ(CaptureOrder(names), (std::vector<size_t>{1, 2, 0}));
}

TEST(ImageOrder, TheOrderOptionOverridesWhatTheNamesSuggest) {
  const std::vector<std::string> frames = {"f_1.png", "f_2.png"}, photos = {"a.jpg", "b.jpg"};
  EXPECT_TRUE(IsSequentialInput(InputOrder::kAuto, frames));
  EXPECT_FALSE(IsSequentialInput(InputOrder::kAuto, photos));
  EXPECT_TRUE(IsSequentialInput(InputOrder::kSequential, photos));
  EXPECT_FALSE(IsSequentialInput(InputOrder::kUnordered, frames));
}

}  // namespace
}  // namespace ramap
