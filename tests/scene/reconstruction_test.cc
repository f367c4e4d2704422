// ModelOfPoses: a model of cameras alone, one image per pose, ids in name order, camera 1.
#include "ramap/scene/reconstruction.h"

#include <gtest/gtest.h>

#include "test_support.h"

namespace ramap {
namespace {

TEST(Reconstruction, ModelOfPosesNumbersTheImagesInNameOrderThroughCameraOne) {
  const Rigid3d a(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY())),
                  Eigen::Vector3d(1, 2, 3));
  const Rigid3d b(Eigen::Quaterniond::Identity(), Eigen::Vector3d(-4, 0, 0));
  const Rigid3d c(Eigen::Quaterniond(Eigen::AngleAxisd(-1.0, Eigen::Vector3d::UnitX())),
                  Eigen::Vector3d(0, 0, 9));
  Camera camera = test::VgaPinholeCamera(700, 710);
  camera.camera_id = 5;  // the model's camera is camera 1 whatever id it had
  const Reconstruction model =
      ModelOfPoses({{"frame_b.png", b}, {"frame_c.png", c}, {"frame_a.png", a}}, camera);

  ASSERT_EQ(model.cameras.size(), 1u);
  EXPECT_EQ(model.cameras.at(1).camera_id, 1u);
  EXPECT_EQ(model.cameras.at(1).params, camera.params);
  EXPECT_EQ(model.cameras.at(1).model, camera.model);
  ASSERT_EQ(model.images.size(), 3u);
  const std::vector<std::pair<std::string, Rigid3d>> expected = {
      {"frame_a.png", a}, {"frame_b.png", b}, {"frame_c.png", c}};
  uint32_t id = 1;
  for (const auto& [name, pose] : expected) {
    const Image& image = model.images.at(id);
    EXPECT_EQ(image.image_id, id);
    EXPECT_EQ(image.name, name);
    EXPECT_EQ(image.camera_id, 1u);
    // Copied, not computed: bit for bit.
    EXPECT_EQ(image.cam_from_world.rotation.coeffs(), pose.rotation.coeffs());
    EXPECT_EQ(image.cam_from_world.translation, pose.translation);
    EXPECT_TRUE(image.points2D.empty());
    ++id;
  }
  EXPECT_TRUE(model.points3D.empty());
  EXPECT_TRUE(model.rigs.empty());
  EXPECT_TRUE(model.frames.empty());
}

TEST(Reconstruction, ModelOfNoPosesHoldsTheCameraAlone) {
  const Reconstruction model = ModelOfPoses({}, test::VgaPinholeCamera());
  EXPECT_EQ(model.cameras.size(), 1u);
  EXPECT_TRUE(model.images.empty());
}

}  // namespace
}  // namespace ramap
