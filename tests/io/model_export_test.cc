// The model exports: nerfstudio's transforms.json checked against numbers worked out by hand from
// its converter's steps, the PLY's header and size, and models no export can express.
#include "ramap/io/model_export.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

Image MakeImage(uint32_t image_id, const std::string& name, uint32_t camera_id,
                const Eigen::Quaterniond& rotation, const Eigen::Vector3d& translation) {
  Image image;
  image.image_id = image_id;
  image.name = name;
  image.camera_id = camera_id;
  image.cam_from_world = Rigid3d(rotation, translation);
  return image;
}

// Camera 1: PINHOLE 640 x 480 (500, 510, 320, 240); camera 2: SIMPLE_RADIAL 800 x 600 (700, 400,
// 300, 0.01). Image 1 looks along the world's z from (-1, -2, -3); image 2 is turned 90 degrees
// about z and sits at (0, 0, -5).
Reconstruction TwoCameraModel() {
  Reconstruction model;
  model.cameras[1] = Camera{1, CameraModel::kPinhole, 640, 480, {500, 510, 320, 240}, true};
  model.cameras[2] = Camera{2, CameraModel::kSimpleRadial, 800, 600, {700, 400, 300, 0.01}, true};
  model.images[1] = MakeImage(1, "a.png", 1, Eigen::Quaterniond::Identity(), {1, 2, 3});
  const Eigen::Quaterniond quarter_turn(std::sqrt(0.5), 0, 0, std::sqrt(0.5));
  model.images[2] = MakeImage(2, "b.png", 2, quarter_turn, {0, 0, 5});
  Point3D point;
  point.xyz = {1, 2, 3};
  point.color = {10, 20, 30};
  model.points3D[1] = point;
  return model;
}

void ExpectMatrix(const nlohmann::json& actual, const std::vector<std::vector<double>>& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (size_t r = 0; r < expected.size(); ++r) {
    ASSERT_EQ(actual[r].size(), expected[r].size());
    for (size_t c = 0; c < expected[r].size(); ++c) {
      EXPECT_NEAR(actual[r][c].get<double>(), expected[r][c], 1e-9) << "row " << r << " col " << c;
    }
  }
}

// By hand, nerfstudio's steps for image 1: c2w = [I | (-1,-2,-3)]; its columns y and z negated
// (OpenCV to OpenGL axes); rows reordered x, z, y and the new third row negated.
TEST(NerfstudioExport, TwoCamerasGiveEachFrameItsIntrinsicsAndMatrix) {
  const nlohmann::json out = NerfstudioTransforms(TwoCameraModel(), "model");
  EXPECT_FALSE(out.contains("fl_x")) << "two cameras: the intrinsics go with each frame";
  ASSERT_EQ(out["frames"].size(), 2u);
  const nlohmann::json& a = out["frames"][0];
  EXPECT_EQ(a["file_path"], "images/a.png");
  EXPECT_EQ(a["colmap_im_id"], 1);
  ExpectMatrix(a["transform_matrix"], {{1, 0, 0, -1}, {0, 0, -1, -3}, {0, 1, 0, 2}, {0, 0, 0, 1}});
  EXPECT_EQ(a["camera_model"], "OPENCV");
  EXPECT_EQ(a["w"], 640);
  EXPECT_EQ(a["h"], 480);
  EXPECT_DOUBLE_EQ(a["fl_x"].get<double>(), 500);
  EXPECT_DOUBLE_EQ(a["fl_y"].get<double>(), 510);
  EXPECT_DOUBLE_EQ(a["cx"].get<double>(), 320);
  EXPECT_DOUBLE_EQ(a["cy"].get<double>(), 240);
  for (const char* k : {"k1", "k2", "p1", "p2"}) EXPECT_DOUBLE_EQ(a[k].get<double>(), 0.0) << k;

  // Image 2: R = Rz(90), t = (0,0,5); c2w = [Rz(-90) | (0,0,-5)] = [[0,1,0,0],[-1,0,0,0],
  // [0,0,1,-5]]; columns y, z negated: [[0,-1,0,0],[-1,0,0,0],[0,0,-1,-5]]; rows x, z, -y.
  const nlohmann::json& b = out["frames"][1];
  EXPECT_EQ(b["file_path"], "images/b.png");
  EXPECT_EQ(b["colmap_im_id"], 2);
  ExpectMatrix(b["transform_matrix"], {{0, -1, 0, 0}, {0, 0, -1, -5}, {1, 0, 0, 0}, {0, 0, 0, 1}});
  EXPECT_EQ(b["camera_model"], "OPENCV");
  EXPECT_EQ(b["w"], 800);
  EXPECT_EQ(b["h"], 600);
  EXPECT_DOUBLE_EQ(b["fl_x"].get<double>(), 700);
  EXPECT_DOUBLE_EQ(b["fl_y"].get<double>(), 700);
  EXPECT_DOUBLE_EQ(b["cx"].get<double>(), 400);
  EXPECT_DOUBLE_EQ(b["cy"].get<double>(), 300);
  EXPECT_DOUBLE_EQ(b["k1"].get<double>(), 0.01);
  EXPECT_DOUBLE_EQ(b["k2"].get<double>(), 0.0);

  ExpectMatrix(out["applied_transform"], {{1, 0, 0, 0}, {0, 0, 1, 0}, {0, -1, 0, 0}});
  EXPECT_EQ(out["ply_file_path"], "sparse_pc.ply");
}

TEST(NerfstudioExport, OneCameraOfIdOneSharesItsIntrinsicsAtTheTop) {
  Reconstruction model = TwoCameraModel();
  model.cameras.erase(2);
  model.images[2].camera_id = 1;
  model.cameras[1].model = CameraModel::kOpenCVFisheye;
  model.cameras[1].params = {500, 510, 320, 240, 0.1, 0.2, 0.3, 0.4};
  const nlohmann::json out = NerfstudioTransforms(model, "model");
  EXPECT_EQ(out["camera_model"], "OPENCV_FISHEYE");
  EXPECT_DOUBLE_EQ(out["k4"].get<double>(), 0.4);
  EXPECT_FALSE(out["frames"][0].contains("fl_x"));
  EXPECT_FALSE(out["frames"][0].contains("camera_model"));
}

TEST(NerfstudioExport, WritesTheTurnedPointsBesideTransforms) {
  test::TempDir dir;
  WriteNerfstudioExport(TwoCameraModel(), dir / "ns", "model");
  std::ifstream json_file(dir / "ns/transforms.json");
  EXPECT_EQ(nlohmann::json::parse(json_file)["frames"].size(), 2u);
  std::ifstream ply(dir / "ns/sparse_pc.ply", std::ios::binary);
  std::stringstream bytes;
  bytes << ply.rdbuf();
  const std::string data = bytes.str();
  const size_t body = data.find("end_header\n") + 11;
  ASSERT_EQ(data.size() - body, 15u);
  float xyz[3];
  std::memcpy(xyz, data.data() + body, sizeof(xyz));
  // (1, 2, 3) turned as the cameras: (x, z, -y).
  EXPECT_FLOAT_EQ(xyz[0], 1);
  EXPECT_FLOAT_EQ(xyz[1], 3);
  EXPECT_FLOAT_EQ(xyz[2], -2);
  EXPECT_EQ(static_cast<uint8_t>(data[body + 12]), 10);
  test::ExpectInputError([&] { WriteNerfstudioExport(TwoCameraModel(), dir / "ns", "model"); },
                         {"transforms.json", "already exists"});
}

TEST(PlyExport, PointsAndOptionallyCameraCentres) {
  test::TempDir dir;
  WritePointCloudPly(TwoCameraModel(), dir / "points.ply", true, "model");
  std::ifstream ply(dir / "points.ply", std::ios::binary);
  std::stringstream bytes;
  bytes << ply.rdbuf();
  const std::string data = bytes.str();
  EXPECT_NE(data.find("format binary_little_endian 1.0"), std::string::npos);
  EXPECT_NE(data.find("element vertex 3\n"), std::string::npos);
  EXPECT_EQ(data.size() - (data.find("end_header\n") + 11), 3u * 15u);
}

TEST(ModelExportBadInput, NothingIsWrittenForAModelNoExportCanExpress) {
  test::TempDir dir;
  Reconstruction empty = TwoCameraModel();
  empty.images.clear();
  test::ExpectInputError([&] { WriteNerfstudioExport(empty, dir / "a", "sparse/0"); },
                         {"sparse/0", "no image"});

  Reconstruction nan_pose = TwoCameraModel();
  nan_pose.images[2].cam_from_world.translation.x() = std::numeric_limits<double>::quiet_NaN();
  test::ExpectInputError([&] { WriteNerfstudioExport(nan_pose, dir / "b", "sparse/0"); },
                         {"sparse/0", "image 2", "b.png", "NaN"});
  test::ExpectInputError([&] { WritePointCloudPly(nan_pose, dir / "b.ply", true, "sparse/0"); },
                         {"image 2", "NaN"});
  test::ExpectInputError([&] { WriteTumExport(nan_pose, dir / "b.txt", "sparse/0"); },
                         {"sparse/0", "image 2", "NaN"});
  test::ExpectInputError([&] { WriteTumExport(empty, dir / "a.txt", "sparse/0"); },
                         {"sparse/0", "no image"});

  Reconstruction full_opencv = TwoCameraModel();
  full_opencv.cameras[2].model = CameraModel::kFullOpenCV;
  full_opencv.cameras[2].params.assign(12, 0.0);
  test::ExpectInputError([&] { WriteNerfstudioExport(full_opencv, dir / "c", "sparse/0"); },
                         {"sparse/0", "camera 2", "FULL_OPENCV", "cannot express"});

  Reconstruction no_points = TwoCameraModel();
  no_points.points3D.clear();
  test::ExpectInputError([&] { WritePointCloudPly(no_points, dir / "d.ply", false, "sparse/0"); },
                         {"sparse/0", "no 3D point"});
  EXPECT_TRUE(fs::is_empty(dir.path())) << "a refused export leaves nothing behind";
}

}  // namespace
}  // namespace ramap
