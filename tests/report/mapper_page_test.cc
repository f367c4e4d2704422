// The data of `ramap mapper`'s report.html: every model with a share of the point budget as large
// as its share of the points, about the largest model's middle, the images in capture order, the
// stage bar and the summary.
#include "ramap/report/mapper_page.h"

#include <gtest/gtest.h>

#include "test_support.h"

namespace ramap {
namespace {

// A model of `names` at centres (x, 0, 0) for x = first, first + 1, ..., and `num_points` points.
Reconstruction Model(const std::vector<std::string>& names, double first, int num_points) {
  Reconstruction model;
  model.cameras[1] = test::VgaPinholeCamera();
  for (size_t k = 0; k < names.size(); ++k) {
    Image image;
    image.image_id = static_cast<uint32_t>(k + 1);
    image.camera_id = 1;
    image.name = names[k];
    image.cam_from_world.translation = Eigen::Vector3d(-(first + k), 0, 0);
    model.images[image.image_id] = image;
  }
  for (int k = 0; k < num_points; ++k) model.points3D[k + 1].xyz = Eigen::Vector3d(k, 1, 10);
  return model;
}

TEST(MapperPage, ModelsShareThePointBudgetAboutTheLargestModelsMiddle) {
  const std::vector<Reconstruction> models = {Model({"f_3.png", "f_4.png", "f_5.png"}, 10, 300),
                                              Model({"f_1.png", "f_2.png"}, 0, 100)};
  const nlohmann::json summary = {{"num_images", 6}, {"num_registered_images", 5}};
  ReportSceneOptions options;
  options.max_points = 40;
  const nlohmann::json data = MapperPageData(
      models, summary, {{"bearings", 0.5}, {"rotation averaging", 1.25}}, "drive", options);
  EXPECT_EQ(data["kind"], "mapper");
  EXPECT_EQ(data["title"], "drive");
  EXPECT_EQ(data["subtitle"], "ramap mapper: 5 of 6 images registered in 2 model(s)");
  EXPECT_TRUE(data["reference"].is_null());
  EXPECT_EQ(data["summary"], summary);
  // The first (largest) model's mean camera centre: (11, 0, 0).
  EXPECT_EQ(data["origin"], nlohmann::json({11, 0, 0}));
  ASSERT_EQ(data["models"].size(), 2u);
  EXPECT_EQ(data["models"][0]["name"], "model 0");
  EXPECT_EQ(data["models"][1]["name"], "model 1");
  // 40 points shared 300 : 100.
  EXPECT_EQ(data["models"][0]["points"]["count"], 30);
  EXPECT_EQ(data["models"][1]["points"]["count"], 10);
  // Every model about the same origin: model 1's first camera at (0, 0, 0) - (11, 0, 0).
  EXPECT_EQ(data["models"][1]["images"]["center"][0], -11);
  // Every registered image, in capture order across the models.
  EXPECT_EQ(data["image_order"],
            nlohmann::json({"f_1.png", "f_2.png", "f_3.png", "f_4.png", "f_5.png"}));
  EXPECT_EQ(data["stage_seconds"], nlohmann::json::parse(R"([{"name": "ramap mapper", "stages":
                                        [["bearings", 0.5], ["rotation averaging", 1.25]]}])"));
  EXPECT_EQ(data["summary_title"], "The mapper's summary");
}

TEST(MapperPage, NoModelsStillMakeAPage) {
  const nlohmann::json data = MapperPageData({}, nlohmann::json::object(), {}, "empty");
  EXPECT_EQ(data["subtitle"], "ramap mapper: 0 of 0 images registered in 0 model(s)");
  EXPECT_TRUE(data["models"].empty());
  EXPECT_EQ(data["origin"], nlohmann::json({0, 0, 0}));
  EXPECT_TRUE(data["image_order"].empty());
}

TEST(MapperPage, StageBarAndImageOrder) {
  EXPECT_EQ(StageBarJson("COLMAP", {{"total", 12.5}}),
            nlohmann::json::parse(R"({"name": "COLMAP", "stages": [["total", 12.5]]})"));
  // Frame numbers sort numerically within their prefix.
  EXPECT_EQ(ImageOrderJson({"img_10.jpg", "img_9.jpg", "img_100.jpg"}),
            nlohmann::json({"img_9.jpg", "img_10.jpg", "img_100.jpg"}));
}

}  // namespace
}  // namespace ramap
