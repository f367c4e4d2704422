// Ground truth readers on the real files of /work/shared/data, the TUM writer, and defects.
#include "ramap/io/trajectory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "ramap/io/colmap_model.h"
#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {
namespace fs = std::filesystem;
using test::TempDir;

// The numbers on line `line_number` (1-based) of a text file, read independently of the reader.
std::vector<double> NumbersOnLine(const std::string& path, int line_number) {
  std::ifstream file(path);
  std::string line;
  for (int k = 0; k < line_number; ++k) std::getline(file, line);
  std::istringstream stream(line);
  std::vector<double> values;
  std::string token;
  while (stream >> token) {
    try {
      values.push_back(std::stod(token));
    } catch (...) {
    }
  }
  return values;
}

void ExpectRotation(const Rigid3d& pose) {
  const Eigen::Matrix3d R = pose.rotation.toRotationMatrix();
  EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
}

using test::ExpectInputError;

TEST(Trajectory, FormatNames) {
  EXPECT_EQ(GroundTruthFormatFromName("kitti"), GroundTruthFormat::kKitti);
  EXPECT_EQ(GroundTruthFormatFromName("strecha"), GroundTruthFormat::kStrecha);
  EXPECT_THROW(GroundTruthFormatFromName("KITTI2"), InputError);
}

TEST(Trajectory, KittiTutorialPoses) {
  RAMAP_REQUIRE_SHARED_DATA(path, "kitti_3dv_tutorial/kitti07_first160/poses_gt.txt");
  const GroundTruth gt = ReadGroundTruth(path, GroundTruthFormat::kKitti);
  EXPECT_TRUE(gt.matched_by_index);
  ASSERT_EQ(gt.poses.size(), 160u);
  EXPECT_LT(gt.poses[0].cam_from_world.rotation.angularDistance(Eigen::Quaterniond::Identity()),
            1e-9);
  EXPECT_LT(gt.poses[0].cam_from_world.translation.norm(), 1e-9);
  // The file holds camera-to-world: its last column is the camera centre.
  for (const int line : {2, 80, 160}) {
    const std::vector<double> v = NumbersOnLine(path, line);
    ASSERT_EQ(v.size(), 12u);
    const Rigid3d& pose = gt.poses[line - 1].cam_from_world;
    ExpectRotation(pose);
    EXPECT_LT((CameraCenter(pose) - Eigen::Vector3d(v[3], v[7], v[11])).norm(), 1e-5) << line;
    EXPECT_NEAR(pose.rotation.toRotationMatrix()(0, 1), v[4], 1e-5);  // R_cw = R_wc^T
  }
  // Matched by index against the image names, in name order.
  std::vector<std::string> names;
  for (int i = 159; i >= 0; --i) {
    char name[16];
    std::snprintf(name, sizeof(name), "%06d.png", i);
    names.push_back(name);
  }
  const std::map<std::string, Rigid3d> by_name = GroundTruthByImageName(gt, names);
  ASSERT_EQ(by_name.size(), 160u);
  EXPECT_EQ(by_name.at("000079.png").translation, gt.poses[79].cam_from_world.translation);
  names.push_back("000160.png");
  EXPECT_THROW(GroundTruthByImageName(gt, names), InputError);
}

TEST(Trajectory, StrechaFountainCameras) {
  RAMAP_REQUIRE_SHARED_DATA(path, "strecha/fountain-P11/gt_dense_cameras");
  const GroundTruth gt = ReadGroundTruth(path, GroundTruthFormat::kStrecha);
  EXPECT_FALSE(gt.matched_by_index);
  ASSERT_EQ(gt.poses.size(), 11u);
  EXPECT_EQ(gt.poses[0].image_name, "0000.jpg");
  EXPECT_EQ(gt.poses[10].image_name, "0010.jpg");
  for (const GroundTruthPose& pose : gt.poses) {
    const std::string file = path + "/" + pose.image_name + ".camera";
    const std::vector<double> c = NumbersOnLine(file, 8);
    ASSERT_EQ(c.size(), 3u);
    ExpectRotation(pose.cam_from_world);
    // The centre is the file's C, and x_cam = R^T (X - C): the file's first row of R (camera-to-
    // world) is the first column of cam_from_world's rotation.
    EXPECT_LT((CameraCenter(pose.cam_from_world) - Eigen::Vector3d(c[0], c[1], c[2])).norm(), 1e-4)
        << pose.image_name;
    const std::vector<double> row = NumbersOnLine(file, 5);
    const Eigen::Matrix3d R = pose.cam_from_world.rotation.toRotationMatrix();
    EXPECT_LT((R.col(0) - Eigen::Vector3d(row[0], row[1], row[2])).norm(), 1e-5);
    EXPECT_LT((pose.cam_from_world * Eigen::Vector3d(c[0], c[1], c[2])).norm(), 1e-4);
  }
}

TEST(Trajectory, MiddleburyTempleRing) {
  RAMAP_REQUIRE_SHARED_DATA(path, "middlebury_templeRing/templeR_par.txt");
  const GroundTruth gt = ReadGroundTruth(path, GroundTruthFormat::kMiddlebury);
  ASSERT_EQ(gt.poses.size(), 47u);
  EXPECT_EQ(gt.poses[0].image_name, "templeR0001.png");
  // Line 2 is image 1: K(9) R(9) t(3), world-to-camera.
  const std::vector<double> v = NumbersOnLine(path, 2);
  ASSERT_EQ(v.size(), 21u);
  const Rigid3d& pose = gt.poses[0].cam_from_world;
  EXPECT_LT((pose.translation - Eigen::Vector3d(v[18], v[19], v[20])).norm(), 1e-12);
  EXPECT_NEAR(pose.rotation.toRotationMatrix()(1, 2), v[9 + 5], 1e-6);
  // A ring around the object: every centre at about the same distance from their mean.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const GroundTruthPose& p : gt.poses) mean += CameraCenter(p.cam_from_world) / 47.0;
  double min_radius = 1e9, max_radius = 0;
  for (const GroundTruthPose& p : gt.poses) {
    ExpectRotation(p.cam_from_world);
    const double radius = (CameraCenter(p.cam_from_world) - mean).norm();
    min_radius = std::min(min_radius, radius);
    max_radius = std::max(max_radius, radius);
  }
  EXPECT_GT(min_radius, 0.8 * max_radius) << min_radius << " " << max_radius;
}

TEST(Trajectory, LundDoorColmapReference) {
  RAMAP_REQUIRE_SHARED_DATA(path, "lund_door/colmap_ground_truth");
  const GroundTruth gt = ReadGroundTruth(path, GroundTruthFormat::kColmap);
  ASSERT_EQ(gt.poses.size(), 12u);
  EXPECT_EQ(gt.poses[0].image_name, "DSC_0001.JPG");
  const Reconstruction model = ReadColmapModelText(path);
  EXPECT_EQ(model.points3D.size(), 11384u);
  for (const GroundTruthPose& pose : gt.poses) {
    ExpectRotation(pose.cam_from_world);
    for (const auto& [id, image] : model.images) {
      if (image.name != pose.image_name) continue;
      EXPECT_LT(image.cam_from_world.rotation.angularDistance(pose.cam_from_world.rotation), 1e-5);
      EXPECT_EQ(image.cam_from_world.translation, pose.cam_from_world.translation);
    }
  }
  std::vector<std::string> names = {"DSC_0003.JPG", "not_there.JPG"};
  const std::map<std::string, Rigid3d> by_name = GroundTruthByImageName(gt, names);
  ASSERT_EQ(by_name.size(), 1u);
  EXPECT_EQ(by_name.count("DSC_0003.JPG"), 1u);
}

TEST(Trajectory, TumFreiburg1Xyz) {
  RAMAP_REQUIRE_SHARED_DATA(path, "gt_trajectories/tum_rgbd/freiburg1_xyz-groundtruth.txt");
  const GroundTruth gt = ReadGroundTruth(path, GroundTruthFormat::kTum);
  EXPECT_TRUE(gt.has_timestamps);
  int data_lines = 0;
  {
    std::ifstream file(path);
    for (std::string line; std::getline(file, line);) data_lines += !line.empty() && line[0] != '#';
  }
  ASSERT_EQ(gt.poses.size(), static_cast<size_t>(data_lines));
  ASSERT_GT(data_lines, 100);
  // First line: 1305031098.6659 1.3563 0.6305 1.6380 0.6132 0.5962 -0.3311 -0.3986
  const std::vector<double> v = NumbersOnLine(path, 4);
  ASSERT_EQ(v.size(), 8u);
  EXPECT_EQ(gt.poses[0].timestamp, v[0]);
  EXPECT_LT((CameraCenter(gt.poses[0].cam_from_world) - Eigen::Vector3d(v[1], v[2], v[3])).norm(),
            1e-12);
  const Eigen::Quaterniond world_from_cam(v[7], v[4], v[5], v[6]);
  EXPECT_LT(
      gt.poses[0].cam_from_world.rotation.angularDistance(world_from_cam.normalized().conjugate()),
      1e-12);
  // Images named by their timestamps match by timestamp, whatever their order.
  char name[64];
  std::snprintf(name, sizeof(name), "%.4f.png", gt.poses[5].timestamp);
  std::vector<std::string> names = {name};
  std::map<std::string, Rigid3d> by_name = GroundTruthByImageName(gt, names);
  ASSERT_EQ(by_name.size(), 1u);
  EXPECT_EQ(by_name.at(name).translation, gt.poses[5].cam_from_world.translation);
  // Otherwise by index, which needs one pose per image: two images for 3000 poses are refused,
  // naming the file, rather than paired with the first two poses.
  names = {"b.png", name};
  test::ExpectInputError([&] { GroundTruthByImageName(gt, names); }, {path});
  // A subset of a sequence named by frame numbers is matched by those numbers.
  names = {"000005.png", "000100.png"};
  by_name = GroundTruthByImageName(gt, names);
  ASSERT_EQ(by_name.size(), 2u);
  EXPECT_EQ(by_name.at("000100.png").translation, gt.poses[100].cam_from_world.translation);
}

Reconstruction TrajectoryModel(const std::vector<std::string>& names) {
  Reconstruction model;
  for (size_t i = 0; i < names.size(); ++i) {
    Image image;
    image.image_id = static_cast<uint32_t>(10 - i);
    image.name = names[i];
    image.cam_from_world = Rigid3d(
        Eigen::Quaterniond(Eigen::AngleAxisd(0.3 * i + 0.1, Eigen::Vector3d(1, i, 2).normalized())),
        Eigen::Vector3d(i * 1.5, -1.0 / 3.0, 2e3 + i));
    model.images[image.image_id] = image;
  }
  return model;
}

TEST(Trajectory, TumWriteReadRoundTrip) {
  TempDir dir;
  for (const std::vector<std::string>& names :
       {std::vector<std::string>{"000007.png", "000003.png", "000120.png", "1305031098.6659.png"},
        std::vector<std::string>{"frame_b.jpg", "frame_a.jpg", "0003.jpg"}}) {
    const Reconstruction model = TrajectoryModel(names);
    const std::string path = dir / "trajectory.txt";
    WriteTumTrajectory(model, path);
    const GroundTruth gt = ReadGroundTruth(path, GroundTruthFormat::kTum);
    ASSERT_EQ(gt.poses.size(), names.size());
    const std::map<std::string, Rigid3d> by_name = GroundTruthByImageName(gt, names);
    ASSERT_EQ(by_name.size(), names.size());
    for (const auto& [id, image] : model.images) {
      const Rigid3d& pose = by_name.at(image.name);
      EXPECT_LT(pose.rotation.angularDistance(image.cam_from_world.rotation), 1e-12) << image.name;
      EXPECT_LT((pose.translation - image.cam_from_world.translation).norm(), 1e-9) << image.name;
    }
  }
  // Numbered names give the numbers as timestamps, in name order.
  const GroundTruth gt = ReadGroundTruth(dir / "trajectory.txt", GroundTruthFormat::kTum);
  EXPECT_EQ(gt.poses[0].timestamp, 0.0);  // last round: names are not all numbers -> indices
  WriteTumTrajectory(TrajectoryModel({"000007.png", "000003.png"}), dir / "numbered.txt");
  const GroundTruth numbered = ReadGroundTruth(dir / "numbered.txt", GroundTruthFormat::kTum);
  ASSERT_EQ(numbered.poses.size(), 2u);
  EXPECT_EQ(numbered.poses[0].timestamp, 3.0);
  EXPECT_EQ(numbered.poses[1].timestamp, 7.0);
}

TEST(Trajectory, BadLinesNameFileAndLine) {
  TempDir dir;
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return dir / name;
  };
  const std::string identity = "1 0 0 0 0 1 0 0 0 0 1 0\n";
  ExpectInputError(
      [&] {
        ReadGroundTruth(write("k1.txt", identity + "1 0 0 0 0 1 0 0 0 0 1\n"),
                        GroundTruthFormat::kKitti);
      },
      {"k1.txt:2", "expected 12 values"});
  ExpectInputError(
      [&] {
        ReadGroundTruth(write("k2.txt", identity + "1 0 0 0 0 1 0 0 0 0 1.01 0\n"),
                        GroundTruthFormat::kKitti);
      },
      {"k2.txt:2", "not orthonormal"});
  ExpectInputError(
      [&] {
        ReadGroundTruth(write("k3.txt", "1 0 0 0 0 1 0 0 0 0 -1 0\n"), GroundTruthFormat::kKitti);
      },
      {"k3.txt:1", "determinant"});
  ExpectInputError(
      [&] {
        ReadGroundTruth(write("k4.txt", "1 0 0 nan 0 1 0 0 0 0 1 0\n"), GroundTruthFormat::kKitti);
      },
      {"k4.txt:1", "'nan'", "not a finite"});
  // Within tolerance: accepted and made exactly orthonormal.
  const GroundTruth near = ReadGroundTruth(write("k5.txt", "1.00002 0 0 0 0 1 0 0 0 0 1 0\n"),
                                           GroundTruthFormat::kKitti);
  ExpectRotation(near.poses[0].cam_from_world);
  ExpectInputError(
      [&] {
        ReadGroundTruth(write("t1.txt", "# c\n1 0 0 0 0 0 0 1\n2 0 0 0 0 0 x 1\n"),
                        GroundTruthFormat::kTum);
      },
      {"t1.txt:3", "'x'"});
  ExpectInputError(
      [&] { ReadGroundTruth(write("t2.txt", "1 0 0 0 0 0 0 2\n"), GroundTruthFormat::kTum); },
      {"t2.txt:1", "norm"});
  ExpectInputError(
      [&] {
        ReadGroundTruth(write("m1.txt", "2\na.png 1 0 0 0 1 0 0 0 1 1 0 0 0 1 0 0 0 1 0 0 0\n"),
                        GroundTruthFormat::kMiddlebury);
      },
      {"m1.txt", "announces 2 images but lists 1"});
  ExpectInputError(
      [&] {
        ReadGroundTruth(write("m2.txt", "1\na.png 1 0 0 0 1 0 0 0 1 1 0 0 0 1 0 0 0 1 0 0\n"),
                        GroundTruthFormat::kMiddlebury);
      },
      {"m2.txt:2", "22 fields"});
  fs::create_directories(dir / "strecha");
  std::ofstream(dir / "strecha/0000.jpg.camera") << "1 0 0\n0 1 0\n0 0 1\n0 0 0\n1 0 0\n0 1 0\n";
  ExpectInputError([&] { ReadGroundTruth(dir / "strecha", GroundTruthFormat::kStrecha); },
                   {"0000.jpg.camera", "ends after 6 lines"});
  std::ofstream(dir / "strecha/0000.jpg.camera")
      << "1 0 0\n0 1 0\n0 0 1\n0 0 0\n1 0 0\n0 1 0\n0 1 0\n1 2 3\n640 480\n";
  ExpectInputError([&] { ReadGroundTruth(dir / "strecha", GroundTruthFormat::kStrecha); },
                   {"0000.jpg.camera", "not orthonormal"});
  ExpectInputError([&] { ReadGroundTruth(dir / "missing.txt", GroundTruthFormat::kTum); },
                   {"missing.txt", "not found"});
}

}  // namespace
}  // namespace ramap
