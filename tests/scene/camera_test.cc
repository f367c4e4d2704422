// Camera models by COLMAP's names and integer ids with their parameter counts, and cameras that
// are one camera under several ids.
#include "ramap/scene/camera.h"

#include <gtest/gtest.h>

#include "test_support.h"

namespace ramap {
namespace {

TEST(Camera, ColmapsModelsByNameIdAndParameterCount) {
  // COLMAP's models in the order of their integer ids, with their parameter counts.
  const std::vector<std::pair<std::string, int>> models = {{"SIMPLE_PINHOLE", 3},
                                                           {"PINHOLE", 4},
                                                           {"SIMPLE_RADIAL", 4},
                                                           {"RADIAL", 5},
                                                           {"OPENCV", 8},
                                                           {"OPENCV_FISHEYE", 8},
                                                           {"FULL_OPENCV", 12},
                                                           {"FOV", 5},
                                                           {"SIMPLE_RADIAL_FISHEYE", 4},
                                                           {"RADIAL_FISHEYE", 5},
                                                           {"THIN_PRISM_FISHEYE", 12}};
  for (int id = 0; id < static_cast<int>(models.size()); ++id) {
    const auto& [name, num_params] = models[id];
    const std::optional<CameraModel> by_id = CameraModelFromId(id);
    ASSERT_TRUE(by_id.has_value()) << id;
    EXPECT_EQ(static_cast<int>(*by_id), id);
    EXPECT_EQ(CameraModelName(*by_id), name);
    EXPECT_EQ(CameraModelFromName(name), by_id);
    EXPECT_EQ(NumCameraParams(*by_id), num_params) << name;
  }
  EXPECT_FALSE(CameraModelFromId(-1).has_value());
  EXPECT_FALSE(CameraModelFromId(11).has_value());
  EXPECT_FALSE(CameraModelFromName("pinhole").has_value());  // COLMAP's names are upper case
  EXPECT_FALSE(CameraModelFromName("EQUIRECTANGULAR").has_value());
}

TEST(Camera, IdenticalCamerasMapToTheLowestIdOfTheirKind) {
  std::map<uint32_t, Camera> cameras;
  for (uint32_t id = 1; id <= 6; ++id) {
    cameras[id] = test::VgaPinholeCamera(500, 500);
    cameras[id].camera_id = id;
  }
  cameras[3].params[0] = 501;                // other parameters
  cameras[5].params[0] = 501;                // ... the same as camera 3's
  cameras[4].has_prior_focal_length = true;  // another source
  cameras[6].width = 641;                    // another size
  EXPECT_EQ(IdenticalCameras(cameras),
            (std::map<uint32_t, uint32_t>{{1, 1}, {2, 1}, {3, 3}, {4, 4}, {5, 3}, {6, 6}}));
  EXPECT_TRUE(IdenticalCameras({}).empty());
}

}  // namespace
}  // namespace ramap
