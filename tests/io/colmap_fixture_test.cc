// Checks the shared COLMAP fixture itself on a tiny real subset, so a broken COLMAP install shows
// up as one clear failure.
#include <filesystem>

#include <gtest/gtest.h>

#include "test_support.h"

namespace ramap::test {
namespace {

TEST(ColmapFixture, BuildsDatabaseAndModelFromRealImages) {
  RAMAP_REQUIRE_COLMAP();
  RAMAP_REQUIRE_SHARED_DATA(images, "strecha/Herz-Jesus-P8/images");
  const ColmapRun run = HerzJesusFourImages(images);
  const std::string model = CachedColmapModel(run);
  ASSERT_FALSE(model.empty());
  EXPECT_TRUE(std::filesystem::exists(model + "/cameras.bin"));
}

}  // namespace
}  // namespace ramap::test
