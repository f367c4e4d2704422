// COLMAP sparse models: bit-identical round trips, compatibility with the real `colmap` binary in
// both directions, and a clear InputError for every kind of defect.
#include "ramap/io/colmap_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <regex>
#include <string>

#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {
namespace fs = std::filesystem;
using test::TempDir;

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// Three cameras of different models, four images (one observes nothing, one has no keypoints at
// all), points with tracks of two and three, awkward values (negative, tiny, huge, many digits).
Reconstruction HandBuiltModel() {
  Reconstruction model;
  Camera simple_radial{3, CameraModel::kSimpleRadial, 640, 480, {500.25, 320.0, 240.5, -0.0123}};
  Camera opencv{7,
                CameraModel::kOpenCV,
                1226,
                370,
                {707.0912, 707.0912, 601.8873, 183.1104, 1e-3, -2e-5, 1.0 / 3.0, 0.0}};
  Camera full{11,
              CameraModel::kFullOpenCV,
              3072,
              2048,
              {2759.48, 2764.16, 1520.69, 1006.81, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8}};
  for (const Camera& camera : {simple_radial, opencv, full})
    model.cameras[camera.camera_id] = camera;

  const auto make_image = [&](uint32_t id, uint32_t camera_id, const std::string& name,
                              const Eigen::Vector3d& axis, double angle, const Eigen::Vector3d& t,
                              int num_points) {
    Image image;
    image.image_id = id;
    image.camera_id = camera_id;
    image.name = name;
    image.cam_from_world =
        Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized())), t);
    for (int k = 0; k < num_points; ++k) {
      Point2D point;
      point.xy = Eigen::Vector2d(10.5 + 17.25 * k + id / 7.0, 3.0 * k + M_PI);
      image.points2D.push_back(point);
    }
    model.images[id] = image;
  };
  make_image(2, 3, "b/img_002.png", {0, 1, 0}, 0.1, {1e-9, -2.5, 1e6 / 3.0}, 5);
  make_image(5, 7, "img_005.png", {1, 2, 3}, -0.7, {0.1, 0.2, 0.3}, 4);
  make_image(9, 11, "img_009.jpg", {0, 0, 1}, 3.0, {-7.28137, -7.57667, 0.204446}, 3);
  make_image(12, 3, "unobserved.png", {1, 0, 0}, 1e-4, {0, 0, 0}, 6);  // observes no 3D point
  make_image(20, 3, "no_keypoints.png", {1, 1, 0}, 0.5, {1, 1, 1}, 0);

  const auto add_point = [&](uint64_t id, const Eigen::Vector3d& xyz, double error,
                             std::vector<TrackElement> track) {
    Point3D point;
    point.xyz = xyz;
    point.color = Eigen::Matrix<uint8_t, 3, 1>(static_cast<uint8_t>(id * 40), 0, 255);
    point.error = error;
    point.track = track;
    for (const TrackElement& element : track) {
      model.images[element.image_id].points2D[element.point2D_idx].point3D_id = id;
    }
    model.points3D[id] = point;
  };
  add_point(1, {1.0 / 7.0, -2e-300, 5e300}, 0.5, {{2, 0}, {5, 1}, {9, 2}});
  add_point(4, {-3, 4, 5}, -1.0, {{5, 0}, {2, 4}});
  add_point(3000000000ull, {0.1, 0.2, 0.3}, 1.25, {{9, 0}, {2, 2}});
  return model;
}

// Exact equality, except that rotations may differ by `rotation_tolerance` (COLMAP renormalises
// every quaternion it reads, which may change its last bit).
void ExpectSameModel(const Reconstruction& a, const Reconstruction& b,
                     double rotation_tolerance = 0.0) {
  ASSERT_EQ(a.cameras.size(), b.cameras.size());
  for (const auto& [id, camera] : a.cameras) {
    ASSERT_EQ(b.cameras.count(id), 1u) << "camera " << id;
    const Camera& other = b.cameras.at(id);
    EXPECT_EQ(camera.camera_id, other.camera_id);
    EXPECT_EQ(camera.model, other.model);
    EXPECT_EQ(camera.width, other.width);
    EXPECT_EQ(camera.height, other.height);
    EXPECT_EQ(camera.params, other.params) << "camera " << id;
  }
  ASSERT_EQ(a.images.size(), b.images.size());
  for (const auto& [id, image] : a.images) {
    ASSERT_EQ(b.images.count(id), 1u) << "image " << id;
    const Image& other = b.images.at(id);
    EXPECT_EQ(image.name, other.name);
    EXPECT_EQ(image.camera_id, other.camera_id);
    if (rotation_tolerance == 0.0) {
      EXPECT_EQ(image.cam_from_world.rotation.coeffs(), other.cam_from_world.rotation.coeffs());
    } else {
      EXPECT_LT((image.cam_from_world.rotation.coeffs() - other.cam_from_world.rotation.coeffs())
                    .cwiseAbs()
                    .maxCoeff(),
                rotation_tolerance)
          << "image " << id;
    }
    EXPECT_EQ(image.cam_from_world.translation, other.cam_from_world.translation);
    ASSERT_EQ(image.points2D.size(), other.points2D.size()) << "image " << id;
    for (size_t k = 0; k < image.points2D.size(); ++k) {
      EXPECT_EQ(image.points2D[k].xy, other.points2D[k].xy);
      EXPECT_EQ(image.points2D[k].point3D_id, other.points2D[k].point3D_id);
    }
  }
  ASSERT_EQ(a.points3D.size(), b.points3D.size());
  for (const auto& [id, point] : a.points3D) {
    ASSERT_EQ(b.points3D.count(id), 1u) << "point " << id;
    const Point3D& other = b.points3D.at(id);
    EXPECT_EQ(point.xyz, other.xyz);
    EXPECT_EQ(point.color, other.color);
    EXPECT_EQ(point.error, other.error);
    ASSERT_EQ(point.track.size(), other.track.size());
    for (size_t k = 0; k < point.track.size(); ++k) {
      EXPECT_EQ(point.track[k].image_id, other.track[k].image_id);
      EXPECT_EQ(point.track[k].point2D_idx, other.track[k].point2D_idx);
    }
  }
}

void ExpectSameFiles(const std::string& dir_a, const std::string& dir_b, const std::string& ext) {
  for (const std::string name : {"cameras", "images", "points3D"}) {
    const std::string a = test::ReadFileBytes(dir_a + "/" + name + ext);
    const std::string b = test::ReadFileBytes(dir_b + "/" + name + ext);
    EXPECT_FALSE(a.empty()) << name << ext;
    EXPECT_TRUE(a == b) << name << ext << " differs between " << dir_a << " and " << dir_b;
  }
}

using test::ExpectInputError;

TEST(ColmapModel, BinaryRoundTripIsBitIdentical) {
  TempDir dir;
  const Reconstruction model = HandBuiltModel();
  WriteColmapModel(model, dir / "first", ModelFormat::kBinary);
  const Reconstruction read = ReadColmapModelBinary(dir / "first");
  ExpectSameModel(model, read);
  WriteColmapModel(read, dir / "second", ModelFormat::kBinary);
  ExpectSameFiles(dir / "first", dir / "second", ".bin");
  // Writing into an existing folder replaces the files.
  WriteColmapModel(read, dir / "first", ModelFormat::kBinary);
  ExpectSameFiles(dir / "first", dir / "second", ".bin");
  // Exact sizes: the header counts plus the records as COLMAP 3.8 lays them out.
  EXPECT_EQ(test::ReadFileBytes(dir / "first/cameras.bin").size(), 8u + 3 * 24 + 8 * (4 + 8 + 12));
  EXPECT_EQ(test::ReadFileBytes(dir / "first/points3D.bin").size(),
            8u + 3 * (8 + 24 + 3 + 8 + 8) + 8 * 7);
}

TEST(ColmapModel, TextRoundTripIsBitIdenticalAndLossless) {
  TempDir dir;
  const Reconstruction model = HandBuiltModel();
  WriteColmapModel(model, dir / "first", ModelFormat::kText);
  const Reconstruction read = ReadColmapModelText(dir / "first");
  ExpectSameModel(model, read);  // exact doubles: 17 significant digits are enough
  WriteColmapModel(read, dir / "second", ModelFormat::kText);
  ExpectSameFiles(dir / "first", dir / "second", ".txt");

  // bin -> txt -> bin gives the same binary files.
  WriteColmapModel(model, dir / "bin1", ModelFormat::kBinary);
  WriteColmapModel(ReadColmapModel(dir / "bin1"), dir / "txt", ModelFormat::kText);
  WriteColmapModel(ReadColmapModel(dir / "txt"), dir / "bin2", ModelFormat::kBinary);
  ExpectSameFiles(dir / "bin1", dir / "bin2", ".bin");

  // The layout COLMAP 3.8 writes: header comments with counts, -1 for an unobserved point, an
  // empty observation line for an image without keypoints.
  const std::string images = test::ReadFileBytes(dir / "txt/images.txt");
  EXPECT_NE(images.find("# Number of images: 5, mean observations per image: 1.3999999999999999\n"),
            std::string::npos)
      << images;
  EXPECT_NE(images.find("20 "), std::string::npos);
  EXPECT_NE(images.find(" 3 no_keypoints.png\n\n"), std::string::npos);
  EXPECT_NE(images.find(" -1 "), std::string::npos);
  const std::string points = test::ReadFileBytes(dir / "txt/points3D.txt");
  EXPECT_NE(points.find("# Number of points: 3, mean track length: 2.3333333333333335\n"),
            std::string::npos);
  EXPECT_NE(points.find("\n4 -3 4 5 160 0 255 -1 5 0 2 4\n"), std::string::npos) << points;
  const std::string cameras = test::ReadFileBytes(dir / "txt/cameras.txt");
  EXPECT_NE(cameras.find("# Number of cameras: 3\n3 SIMPLE_RADIAL 640 480 500.25 320 240.5"),
            std::string::npos)
      << cameras;
}

TEST(ColmapModel, ReadPicksBinaryWhenBothFormatsArePresent) {
  TempDir dir;
  Reconstruction model = HandBuiltModel();
  WriteColmapModel(model, dir / "m", ModelFormat::kText);
  model.cameras.at(3).params[0] = 999.0;
  // ramap never writes one format beside the other (readers would see the old one)...
  EXPECT_THROW(WriteColmapModel(model, dir / "m", ModelFormat::kBinary), InputError);
  EXPECT_FALSE(fs::exists(dir / "m/cameras.bin"));
  // ...but reads such a folder as COLMAP does, binary first.
  WriteColmapModel(model, dir / "b", ModelFormat::kBinary);
  for (const char* file : {"cameras.bin", "images.bin", "points3D.bin"}) {
    fs::copy_file(dir / ("b/" + std::string(file)), dir / ("m/" + std::string(file)));
  }
  EXPECT_EQ(ReadColmapModel(dir / "m").cameras.at(3).params[0], 999.0);
  EXPECT_EQ(ReadColmapModelText(dir / "m").cameras.at(3).params[0], 500.25);
}

// COLMAP itself reads what ramap writes: its analyser counts the same, and its own text
// conversion reads back as the model we wrote.
TEST(ColmapModel, ColmapBinaryReadsWhatRamapWrote) {
  RAMAP_REQUIRE_COLMAP();
  TempDir dir;
  const Reconstruction model = HandBuiltModel();
  WriteColmapModel(model, dir / "ours", ModelFormat::kBinary);
  const test::CommandResult analysis =
      test::RunCommand("colmap model_analyzer --path '" + (dir / "ours") + "'");
  ASSERT_EQ(analysis.exit_code, 0) << analysis.output;
  EXPECT_NE(analysis.output.find("Cameras: 3\n"), std::string::npos) << analysis.output;
  EXPECT_NE(analysis.output.find("Registered images: 5\n"), std::string::npos) << analysis.output;
  EXPECT_NE(analysis.output.find("Points: 3\n"), std::string::npos) << analysis.output;
  EXPECT_NE(analysis.output.find("Observations: 7\n"), std::string::npos) << analysis.output;

  for (const std::string source : {"ours", "ours_txt"}) {
    if (source == "ours_txt") WriteColmapModel(model, dir / source, ModelFormat::kText);
    const std::string out = dir / (source + "_colmap");
    fs::create_directories(out);
    const test::CommandResult convert =
        test::RunCommand("colmap model_converter --input_path '" + (dir / source) +
                         "' --output_path '" + out + "' --output_type TXT");
    ASSERT_EQ(convert.exit_code, 0) << convert.output;
    ExpectSameModel(model, ReadColmapModelText(out), 1e-15);
  }
}

// A model COLMAP's mapper made from real images: read as .bin and as COLMAP's own text
// conversion; both agree, and our text output equals COLMAP's line for line (COLMAP writes points
// in hash order, we in id order).
TEST(ColmapModel, ReadsModelColmapMadeFromRealImages) {
  RAMAP_REQUIRE_COLMAP();
  RAMAP_REQUIRE_SHARED_DATA(images, "strecha/Herz-Jesus-P8/images");
  const std::string colmap_model = test::CachedColmapModel(test::HerzJesusFourImages(images));
  ASSERT_FALSE(colmap_model.empty());
  TempDir dir;
  const std::string colmap_txt = dir / "colmap_txt";
  fs::create_directories(colmap_txt);
  const test::CommandResult convert =
      test::RunCommand("colmap model_converter --input_path '" + colmap_model +
                       "' --output_path '" + colmap_txt + "' --output_type TXT");
  ASSERT_EQ(convert.exit_code, 0) << convert.output;

  const Reconstruction from_bin = ReadColmapModelBinary(colmap_model);
  const Reconstruction from_txt = ReadColmapModelText(colmap_txt);
  ExpectSameModel(from_bin, from_txt);
  EXPECT_EQ(from_bin.cameras.size(), 1u);
  EXPECT_EQ(from_bin.cameras.begin()->second.model, CameraModel::kPinhole);
  EXPECT_GE(from_bin.images.size(), 3u);
  EXPECT_GT(from_bin.points3D.size(), 100u);
  for (const auto& [id, image] : from_bin.images) {
    EXPECT_TRUE(std::regex_match(image.name, std::regex("000[0-3]\\.jpg"))) << image.name;
    EXPECT_NEAR(image.cam_from_world.rotation.norm(), 1.0, 1e-9);
  }

  // cameras.bin and images.bin come out byte for byte as COLMAP wrote them (ids ascending there
  // too); points3D.bin holds the same records in another order.
  WriteColmapModel(from_bin, dir / "ours_bin", ModelFormat::kBinary);
  EXPECT_EQ(test::ReadFileBytes(dir / "ours_bin/cameras.bin"),
            test::ReadFileBytes(colmap_model + "/cameras.bin"));
  EXPECT_EQ(test::ReadFileBytes(dir / "ours_bin/images.bin"),
            test::ReadFileBytes(colmap_model + "/images.bin"));
  EXPECT_EQ(test::ReadFileBytes(dir / "ours_bin/points3D.bin").size(),
            test::ReadFileBytes(colmap_model + "/points3D.bin").size());

  WriteColmapModel(from_bin, dir / "ours_txt", ModelFormat::kText);
  for (const std::string name : {"cameras.txt", "images.txt", "points3D.txt"}) {
    const auto sorted_lines = [](const std::string& path) {
      std::ifstream file(path);
      std::vector<std::string> lines;
      for (std::string line; std::getline(file, line);) lines.push_back(line);
      // images.txt: keep each image's two lines together when sorting.
      std::sort(lines.begin(), lines.end());
      return lines;
    };
    EXPECT_EQ(sorted_lines(dir / ("ours_txt/" + name)), sorted_lines(colmap_txt + "/" + name))
        << name;
  }
}

// ------------------------------------------------------------------------------------------------
// Defects.

class ColmapModelDefects : public ::testing::Test {
 protected:
  void SetUp() override {
    WriteColmapModel(HandBuiltModel(), dir_ / "bin", ModelFormat::kBinary);
    WriteColmapModel(HandBuiltModel(), dir_ / "txt", ModelFormat::kText);
  }
  std::string Bin(const std::string& file) { return dir_ / ("bin/" + file); }
  std::string Txt(const std::string& file) { return dir_ / ("txt/" + file); }
  // Replaces `from` (which must occur) by `to` in a text file of the model.
  void EditText(const std::string& file, const std::string& from, const std::string& to) {
    std::string text = test::ReadFileBytes(Txt(file));
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    WriteBytes(Txt(file), text);
  }
  void PatchBinary(const std::string& file, size_t offset, const void* bytes, size_t size) {
    std::string data = test::ReadFileBytes(Bin(file));
    ASSERT_LE(offset + size, data.size());
    std::memcpy(&data[offset], bytes, size);
    WriteBytes(Bin(file), data);
  }
  void ExpectBinaryError(const std::vector<std::string>& parts) {
    ExpectInputError([&] { ReadColmapModelBinary(dir_ / "bin"); }, parts);
  }
  void ExpectTextError(const std::vector<std::string>& parts) {
    ExpectInputError([&] { ReadColmapModelText(dir_ / "txt"); }, parts);
  }

  TempDir dir_;
};

TEST_F(ColmapModelDefects, MissingFilesAndFolders) {
  fs::remove(Bin("points3D.bin"));
  ExpectBinaryError({"points3D.bin", "file not found"});
  fs::remove(Txt("images.txt"));
  ExpectTextError({"images.txt", "file not found"});
  ExpectInputError([&] { ReadColmapModel(dir_ / "nowhere"); }, {"nowhere", "not found"});
  fs::create_directories(dir_ / "empty");
  ExpectInputError([&] { ReadColmapModel(dir_ / "empty"); }, {"empty", "cameras.bin"});
}

TEST_F(ColmapModelDefects, EveryTruncationOfEveryBinaryFileIsReported) {
  for (const std::string file : {"cameras.bin", "images.bin", "points3D.bin"}) {
    const std::string whole = test::ReadFileBytes(Bin(file));
    for (size_t size = 0; size < whole.size(); ++size) {
      WriteBytes(Bin(file), whole.substr(0, size));
      ExpectInputError([&] { ReadColmapModelBinary(dir_ / "bin"); },
                       {file, "truncated while reading"});
    }
    WriteBytes(Bin(file), whole + "x");
    ExpectBinaryError({file, "unexpected bytes"});
    WriteBytes(Bin(file), whole);
  }
  // The item is named with its position: image 1 takes 4 + 56 + 4 + 14 + 8 + 5 * 24 = 206 bytes.
  const std::string images = test::ReadFileBytes(Bin("images.bin"));
  WriteBytes(Bin("images.bin"), images.substr(0, 8 + 206 + 100));
  ExpectBinaryError({"images.bin: truncated while reading image 2 (of 5)"});
  WriteBytes(Bin("images.bin"), images);
  EXPECT_NO_THROW(ReadColmapModelBinary(dir_ / "bin"));
}

TEST_F(ColmapModelDefects, AbsurdCountIsTruncationNotAnAllocation) {
  const uint64_t huge = uint64_t{1} << 60;
  const std::string points = test::ReadFileBytes(Bin("points3D.bin"));
  PatchBinary("points3D.bin", 0, &huge, 8);
  ExpectBinaryError(
      {"points3D.bin", "truncated while reading 3D point 4 (of 1152921504606846976)"});
  WriteBytes(Bin("points3D.bin"), points);
  PatchBinary("points3D.bin", 8 + 8 + 24 + 3 + 8, &huge, 8);  // track length of the first point
  ExpectBinaryError({"points3D.bin", "truncated while reading 3D point 1 (of 3)"});
  const std::string images = test::ReadFileBytes(Bin("images.bin"));
  PatchBinary("images.bin", 8 + 4 + 56 + 4 + 14, &huge, 8);  // keypoint count of the first image
  ExpectBinaryError({"images.bin", "truncated while reading image 1 (of 5)"});
}

TEST_F(ColmapModelDefects, UnknownCameraModel) {
  const int32_t model_id = 42;
  PatchBinary("cameras.bin", 8 + 4, &model_id, 4);
  ExpectBinaryError({"cameras.bin", "camera 1 (of 3)", "unknown camera model id 42"});
  EditText("cameras.txt", "SIMPLE_RADIAL", "SIMPLE_RADIAL_X");
  ExpectTextError({"cameras.txt", "line 4", "unknown camera model 'SIMPLE_RADIAL_X'"});
}

TEST_F(ColmapModelDefects, WrongParameterCount) {
  EditText("cameras.txt", "500.25 320 240.5 -0.0123", "500.25 320 240.5");
  ExpectTextError({"cameras.txt", "line 4", "camera 3", "takes 4 parameters, found 3"});
}

TEST_F(ColmapModelDefects, NonFinitePoseOrIntrinsics) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  PatchBinary("images.bin", 8 + 4 + 8 * 5, &nan, 8);  // image 2's ty
  ExpectBinaryError({"images.bin", "image 2 ('b/img_002.png')", "NaN or infinite"});
  PatchBinary("cameras.bin", 8 + 24 + 8, &inf, 8);  // camera 3's cx
  ExpectBinaryError({"cameras.bin", "camera 3", "parameter 2", "not a finite"});

  std::string images = test::ReadFileBytes(Txt("images.txt"));
  images = std::regex_replace(images, std::regex("\n12 [^ ]+ "), "\n12 inf ");
  WriteBytes(Txt("images.txt"), images);
  ExpectTextError({"images.txt", "image 12", "not a finite number"});
}

TEST_F(ColmapModelDefects, ImageWithMissingCamera) {
  const uint32_t camera_id = 99;
  PatchBinary("images.bin", 8 + 4 + 56, &camera_id, 4);
  ExpectBinaryError({"images.bin", "image 2 ('b/img_002.png') uses camera 99", "cameras.bin"});
  EditText("images.txt", " 7 img_005.png", " 8 img_005.png");
  ExpectTextError({"images.txt", "image 5 ('img_005.png') uses camera 8", "cameras.txt"});
}

TEST_F(ColmapModelDefects, TrackNamingMissingImageOrPoint) {
  EditText("points3D.txt", " 5 0 2 4\n", " 6 0 2 4\n");
  ExpectTextError({"points3D.txt", "3D point 4 track element 1 (image 6, point2D 0)",
                   "names an image that images.txt does not have"});
  EditText("points3D.txt", " 6 0 2 4\n", " 5 0 2 44\n");
  ExpectTextError(
      {"points3D.txt", "3D point 4 track element 2 (image 2, point2D 44)", "out of range"});
}

TEST_F(ColmapModelDefects, ImagePointNamingMissingPoint3D) {
  // Image 12 observes nothing; make its first observation name point 77.
  std::string images = test::ReadFileBytes(Txt("images.txt"));
  const size_t line = images.find("unobserved.png\n") + std::string("unobserved.png\n").size();
  const size_t first_id = images.find(" -1", line);
  images.replace(first_id, 3, " 77");
  WriteBytes(Txt("images.txt"), images);
  ExpectTextError({"images.txt", "image 12 ('unobserved.png') point2D 0 names 3D point 77",
                   "points3D.txt does not have"});
}

TEST_F(ColmapModelDefects, DuplicateIds) {
  // Second image record starts after the first one (206 bytes); give it the first image's id.
  const uint32_t image_id = 2;
  PatchBinary("images.bin", 8 + 206, &image_id, 4);
  ExpectBinaryError({"images.bin", "image 2 (of 5)", "duplicate image id 2"});
  std::string cameras = test::ReadFileBytes(Txt("cameras.txt"));
  WriteBytes(Txt("cameras.txt"), cameras + "7 PINHOLE 10 10 1 1 5 5\n");
  ExpectTextError({"cameras.txt", "line 7", "duplicate camera id 7"});
}

TEST_F(ColmapModelDefects, TextLinesThatDoNotParse) {
  EditText("points3D.txt", "\n4 -3 4 5 160 0 255", "\n4 -3 4 5 300 0 255");
  ExpectTextError({"points3D.txt", "line 5", "colour of 3D point 4", "'300'"});
  EditText("points3D.txt", "\n4 -3 4 5 300 0 255", "\n4 -3 4 5 160 0 255");
  EditText("points3D.txt", "\n4 -3 4 5", "\n4 -3 4x 5");
  ExpectTextError({"points3D.txt", "line 5", "position of 3D point 4", "'4x'"});
  EditText("points3D.txt", "\n4 -3 4x 5", "\n4 -3 4 5");
  EditText("points3D.txt", " 5 0 2 4\n", " 5 0 2\n");
  ExpectTextError({"points3D.txt", "line 5", "pairs"});
  EditText("points3D.txt", " 5 0 2\n", " 5 0 2 4\n");
  EXPECT_NO_THROW(ReadColmapModelText(dir_ / "txt"));
  EditText("images.txt", " 3 no_keypoints.png", " 3 no keypoints.png");
  ExpectTextError({"images.txt", "line 13", "10 fields"});
}

TEST(ColmapModelWriter, RejectsBadModelAndWritesNothing) {
  TempDir dir;
  const auto expect_rejected = [&](const Reconstruction& model, ModelFormat format,
                                   const std::vector<std::string>& parts) {
    ExpectInputError([&] { WriteColmapModel(model, dir / "out", format); }, parts);
    EXPECT_FALSE(fs::exists(dir / "out"));
    EXPECT_TRUE(fs::is_empty(dir.path())) << "staging left behind";
  };
  Reconstruction model = HandBuiltModel();
  model.images.at(5).camera_id = 4;
  expect_rejected(model, ModelFormat::kBinary, {"out/images.bin", "image 5", "camera 4"});
  model = HandBuiltModel();
  model.images.at(9).cam_from_world.translation.x() = std::nan("");
  expect_rejected(model, ModelFormat::kText, {"out/images.txt", "image 9", "NaN"});
  model = HandBuiltModel();
  model.cameras.at(7).params.pop_back();
  expect_rejected(model, ModelFormat::kBinary, {"out/cameras.bin", "camera 7", "takes 8"});
  model = HandBuiltModel();
  model.points3D.at(4).track.push_back({12, 99});
  expect_rejected(model, ModelFormat::kBinary, {"out/points3D.bin", "3D point 4", "out of range"});
  model = HandBuiltModel();
  model.images.at(12).points2D[1].point3D_id = 5;
  expect_rejected(model, ModelFormat::kBinary, {"out/images.bin", "names 3D point 5"});
  model = HandBuiltModel();
  model.images.at(2).name = "with space.png";
  expect_rejected(model, ModelFormat::kText, {"images.txt", "white space"});
  EXPECT_NO_THROW(WriteColmapModel(model, dir / "out", ModelFormat::kBinary));
  EXPECT_EQ(ReadColmapModel(dir / "out").images.at(2).name, "with space.png");

  // An existing model is left untouched by a rejected write.
  const std::string before = test::ReadFileBytes(dir / "out/images.bin");
  model.images.at(5).camera_id = 4;
  ExpectInputError([&] { WriteColmapModel(model, dir / "out", ModelFormat::kBinary); },
                   {"camera 4"});
  EXPECT_EQ(test::ReadFileBytes(dir / "out/images.bin"), before);
  // The three model files and COLMAP 4's rigs and frames.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "out"), fs::directory_iterator()), 5);

  // A new nested folder, named with a trailing separator: created, nothing else left beside it.
  WriteColmapModel(HandBuiltModel(), dir / "nested/model/", ModelFormat::kText);
  ExpectSameModel(HandBuiltModel(), ReadColmapModel(dir / "nested/model"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "nested"), fs::directory_iterator()), 1);
  // A file where the folder should be.
  std::ofstream(dir / "file") << "x";
  ExpectInputError([&] { WriteColmapModel(HandBuiltModel(), dir / "file"); },
                   {"file", "not a folder"});
}

// The CLI on a truncated model: non-zero exit, the file and item named, no output folder.
TEST(ColmapModelConverterCli, TruncatedModelFailsCleanly) {
  TempDir dir;
  WriteColmapModel(HandBuiltModel(), dir / "in", ModelFormat::kBinary);
  const std::string cli = test::RamapBinary() + " model_converter --input_path '" + (dir / "in") +
                          "' --output_path '" + (dir / "out") + "' --output_type ";
  const test::CommandResult ok = test::RunCommand(cli + "TXT");
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  ExpectSameModel(HandBuiltModel(), ReadColmapModelText(dir / "out"));
  fs::remove_all(dir / "out");

  const std::string points = test::ReadFileBytes(dir / "in/points3D.bin");
  WriteBytes(dir / "in/points3D.bin", points.substr(0, points.size() - 3));
  const test::CommandResult result = test::RunCommand(cli + "BIN");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("points3D.bin: truncated while reading 3D point 3 (of 3)"),
            std::string::npos)
      << result.output;
  EXPECT_FALSE(fs::exists(dir / "out"));

  const test::CommandResult bad_type = test::RunCommand(cli + "VRML");
  EXPECT_NE(bad_type.exit_code, 0);
  EXPECT_NE(bad_type.output.find("'VRML' is not BIN, TXT, PLY, NERFSTUDIO or TUM"),
            std::string::npos)
      << bad_type.output;
}

}  // namespace
}  // namespace ramap
