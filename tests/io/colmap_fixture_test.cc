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
  ColmapRun run;
  run.image_dir = images;
  run.image_names = {"0000.jpg", "0001.jpg", "0002.jpg", "0003.jpg"};
  run.camera_params = "2759.48,2764.16,1520.69,1006.81";
  run.max_image_size = 640;
  const std::string model = CachedColmapModel(run);
  ASSERT_FALSE(model.empty());
  EXPECT_TRUE(std::filesystem::exists(model + "/cameras.bin"));
}

}  // namespace
}  // namespace ramap::test
