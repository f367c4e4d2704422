// report.html without a browser: the page is whole and self-contained, its data survives any
// text a model holds, and the mapper's page holds every registered image (tests/browser opens it).
#include "ramap/report/html_report.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <regex>

#include "ramap/io/colmap_database.h"
#include "ramap/report/mapper_page.h"
#include "ramap/report/report_scene.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

Reconstruction ThreeCameraModel() {
  Reconstruction model;
  model.cameras[1] = test::VgaPinholeCamera();
  for (uint32_t id = 1; id <= 3; ++id) {
    Image image;
    image.image_id = id;
    image.camera_id = 1;
    image.name = "frame_" + std::to_string(id) + ".png";
    image.cam_from_world.translation = Eigen::Vector3d(id, 0, 0);
    image.points2D.push_back({Eigen::Vector2d(320.5, 240.5), 1});
    model.images[id] = image;
  }
  Point3D point;
  point.xyz = Eigen::Vector3d(0, 0, 5);
  for (uint32_t id = 1; id <= 3; ++id) point.track.push_back({id, 0});
  model.points3D[1] = point;
  return model;
}

TEST(HtmlReport, PageIsSelfContainedAndItsDataSurvivesScriptText) {
  Reconstruction model = ThreeCameraModel();
  model.images[2].name = "</script><script>alert(1)</script>.png";
  model.images[3].name = "<!--<script>-->.png";
  const nlohmann::json data =
      MapperPageData({model}, {{"num_images", 3}, {"num_registered_images", 3}},
                     {{"relative poses", 1.5}}, "a <title> & more");
  const std::string page = RenderHtmlReport(data);
  EXPECT_NE(page.find("<title>a &lt;title&gt; &amp; more</title>"), std::string::npos);
  // Exactly the page's own script elements, none from the data.
  EXPECT_EQ(std::count(page.begin(), page.end(), '\0'), 0);
  std::regex closing("</script>");
  EXPECT_EQ(std::distance(std::sregex_iterator(page.begin(), page.end(), closing),
                          std::sregex_iterator()),
            3);
  // Nothing is fetched: no URL in a src or href attribute, no module import.
  EXPECT_FALSE(std::regex_search(page, std::regex("(src|href)=\"(https?:)?//")));
  EXPECT_EQ(page.find("type=\"module\""), std::string::npos);
  EXPECT_NE(page.find("three.js"), std::string::npos) << "the licence of the inlined library";

  test::TempDir dir;
  WriteHtmlReport(data, dir / "report.html");
  const nlohmann::json read = test::ReportPageData(dir / "report.html");
  ASSERT_EQ(read["models"].size(), 1u);
  const nlohmann::json& names = read["models"][0]["images"]["name"];
  for (const char* name : {"</script><script>alert(1)</script>.png", "<!--<script>-->.png"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << names;
  }
  EXPECT_EQ(read["stage_seconds"][0]["stages"][0][0], "relative poses");
}

TEST(HtmlReport, ModelJsonHoldsEveryImageInCaptureOrderWithItsErrors) {
  const Reconstruction model = ThreeCameraModel();
  const nlohmann::json json = ReportModelJson("m", model, Sim3d(), nullptr, 10);
  EXPECT_EQ(json["num_registered"], 3);
  EXPECT_TRUE(json["sequence"]);
  const nlohmann::json& images = json["images"];
  ASSERT_EQ(images["name"].size(), 3u);
  EXPECT_EQ(images["center"].size(), 9u);
  EXPECT_EQ(images["rotation"].size(), 12u);
  // Image 1 sits at -t = (-1, 0, 0).
  EXPECT_DOUBLE_EQ(images["center"][0].get<double>(), -1.0);
  EXPECT_TRUE(images["rotation_error_deg"].is_null()) << "no evaluation, no pose errors";
  // The point (0, 0, 5) seen from (-id, 0, 0) projects id * 100 px right of the centre.
  EXPECT_NEAR(images["reprojection_error_px"][1].get<double>(), 200.0, 1.0);
  EXPECT_EQ(json["points"]["count"], 1);
  EXPECT_TRUE(json["points"]["rgb"].is_null()) << "black points: coloured by height instead";

  Sim3d doubled;
  doubled.scale = 2.0;
  const nlohmann::json scaled = ReportModelJson("m", model, doubled, nullptr, 0);
  EXPECT_DOUBLE_EQ(scaled["images"]["center"][0].get<double>(), -2.0);
  EXPECT_EQ(scaled["points"]["count"], 0) << "a budget of no points";
}

// A scene in UTM coordinates, cameras a millimetre apart 5000 km from the frame's origin: the page
// writes coordinates about the scene's middle, so 7 digits still tell them apart.
TEST(HtmlReport, FarFromTheFramesOriginMillimetresSurvive) {
  Reconstruction model = ThreeCameraModel();
  for (auto& [image_id, image] : model.images) {
    image.cam_from_world.translation = -Eigen::Vector3d(5e6 + 0.001 * image_id, 4e6, 100);
  }
  const nlohmann::json data = MapperPageData({model}, nlohmann::json::object(), {}, "utm");
  EXPECT_NEAR(data["origin"][0].get<double>(), 5e6 + 0.002, 1e-6);
  const nlohmann::json& centers = data["models"][0]["images"]["center"];
  EXPECT_NEAR(centers[3].get<double>() - centers[0].get<double>(), 0.001, 1e-6);
  EXPECT_NEAR(centers[1].get<double>(), 0.0, 1e-6);
}

TEST(HtmlReport, MapperWritesItBesideTheSummary) {
  test::TempDir dir;
  const SyntheticScene scene =
      BuildSyntheticScene(test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kLine, 12));
  const std::string db = dir / "scene.db";
  WriteColmapDatabase(scene.database, db);
  const test::CommandResult run =
      test::RunCommand("'" + test::RamapBinary() + "' mapper --database_path '" + db +
                       "' --output_path '" + (dir / "out") + "' --Mapper.refine 0");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json page = test::ReportPageData(dir / "out/report.html");
  ASSERT_EQ(page["kind"], "mapper");
  ASSERT_EQ(page["models"].size(), 1u);
  EXPECT_EQ(page["models"][0]["images"]["name"].size(), 12u);
  EXPECT_EQ(page["summary"]["num_registered_images"], 12);
  EXPECT_FALSE(page["stage_seconds"][0]["stages"].empty());
}

}  // namespace
}  // namespace ramap
