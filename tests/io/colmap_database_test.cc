#include "ramap/io/colmap_database.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "ramap/io/sqlite.h"
#include "ramap/util/error.h"
#include "ramap/util/timer.h"
#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

// ---------------------------------------------------------------------------------------------
// Building and comparing databases.

Eigen::Quaterniond RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  return Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
}

Keypoints RandomKeypoints(std::mt19937& rng, size_t count, int num_cols) {
  std::uniform_real_distribution<float> uniform(0.f, 1000.f);
  Keypoints keypoints;
  keypoints.num_cols = num_cols;
  keypoints.data.resize(count * num_cols);
  for (float& value : keypoints.data) value = uniform(rng);
  return keypoints;
}

std::vector<FeatureMatch> RandomMatches(std::mt19937& rng, size_t count, size_t num1, size_t num2) {
  std::vector<FeatureMatch> matches(count);
  for (FeatureMatch& match : matches) {
    match.point2D_idx1 = static_cast<uint32_t>(rng() % num1);
    match.point2D_idx2 = static_cast<uint32_t>(rng() % num2);
  }
  return matches;
}

// Every camera model, priors present and absent, keypoints of 2, 4 and 6 columns, descriptors of
// some images, matches (one pair with none) and geometries of several configurations.
FeatureDatabase MakeFullDatabase() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  FeatureDatabase database;
  for (int model_id = 0; model_id <= 10; ++model_id) {
    Camera camera;
    camera.camera_id = model_id + 1;
    camera.model = *CameraModelFromId(model_id);
    camera.width = 640 + model_id;
    camera.height = 480 - model_id;
    for (int i = 0; i < NumCameraParams(camera.model); ++i) {
      camera.params.push_back(i < 2 ? 500.0 + 10 * i + model_id : uniform(rng));
    }
    camera.has_prior_focal_length = model_id % 2 == 0;
    database.cameras[camera.camera_id] = camera;
  }
  const int kNumImages = 8;
  const int kCols[] = {2, 4, 6};
  for (int i = 0; i < kNumImages; ++i) {
    Image image;
    image.image_id = 3 * i + 1;  // gaps in the ids, as after deleting images in COLMAP
    image.name = "folder/image_" + std::to_string(i) + ".jpg";
    image.camera_id = static_cast<uint32_t>(i % 11) + 1;
    if (i % 3 != 2) image.prior_rotation = RandomRotation(rng);
    if (i % 2 == 0) image.prior_translation = Eigen::Vector3d(uniform(rng), uniform(rng), 7.5 * i);
    database.images[image.image_id] = image;
    database.keypoints[image.image_id] = RandomKeypoints(rng, 50 + 10 * i, kCols[i % 3]);
    if (i % 2 == 1) {
      Descriptors descriptors;
      descriptors.num_cols = 128;
      descriptors.data.resize(128 * database.keypoints[image.image_id].size());
      for (uint8_t& value : descriptors.data) value = static_cast<uint8_t>(rng());
      database.descriptors[image.image_id] = descriptors;
    }
  }
  // An image without keypoints, descriptors or pairs.
  Image lonely;
  lonely.image_id = 100;
  lonely.name = "lonely.png";
  lonely.camera_id = 1;
  database.images[lonely.image_id] = lonely;

  const TwoViewConfig kConfigs[] = {TwoViewConfig::kCalibrated, TwoViewConfig::kUncalibrated,
                                    TwoViewConfig::kPlanarOrPanoramic, TwoViewConfig::kDegenerate,
                                    TwoViewConfig::kPanoramic};
  int pair_index = 0;
  for (const auto& [id1, image1] : database.images) {
    for (const auto& [id2, image2] : database.images) {
      if (id1 >= id2 || id2 == lonely.image_id) continue;
      const size_t num1 = database.keypoints.at(id1).size();
      const size_t num2 = database.keypoints.at(id2).size();
      const uint64_t pair_id = ImagePairToPairId(id1, id2);
      const size_t num_matches = pair_index % 7 == 3 ? 0 : 20 + pair_index;
      database.matches[pair_id] = RandomMatches(rng, num_matches, num1, num2);
      if (pair_index % 2 == 0) {
        TwoViewGeometry geometry;
        geometry.image_id1 = id1;
        geometry.image_id2 = id2;
        geometry.config = kConfigs[(pair_index / 2) % 5];
        geometry.inlier_matches = RandomMatches(rng, num_matches / 2, num1, num2);
        geometry.F = Eigen::Matrix3d::Random();
        if (geometry.config == TwoViewConfig::kCalibrated) geometry.E = Eigen::Matrix3d::Random();
        if (geometry.config != TwoViewConfig::kDegenerate) geometry.H = Eigen::Matrix3d::Random();
        geometry.cam2_from_cam1 =
            Rigid3d(RandomRotation(rng), Eigen::Vector3d(uniform(rng), uniform(rng), 1.0));
        database.two_view_geometries[pair_id] = geometry;
      }
      ++pair_index;
    }
  }
  return database;
}

// One camera, three images, two pairs: the base of the broken databases below.
FeatureDatabase MakeSmallDatabase() {
  std::mt19937 rng(3);
  FeatureDatabase database;
  database.cameras[1] = test::VgaPinholeCamera(500, 510);
  for (uint32_t id = 1; id <= 3; ++id) {
    Image image;
    image.image_id = id;
    image.name = "view" + std::to_string(id) + ".jpg";
    image.camera_id = 1;
    database.images[id] = image;
    database.keypoints[id] = RandomKeypoints(rng, 40, 6);
  }
  for (const auto& [id1, id2] : {std::pair<uint32_t, uint32_t>{1, 2}, {2, 3}}) {
    const uint64_t pair_id = ImagePairToPairId(id1, id2);
    database.matches[pair_id] = RandomMatches(rng, 30, 40, 40);
    TwoViewGeometry geometry;
    geometry.image_id1 = id1;
    geometry.image_id2 = id2;
    geometry.config = TwoViewConfig::kCalibrated;
    geometry.inlier_matches = RandomMatches(rng, 20, 40, 40);
    geometry.E = Eigen::Matrix3d::Random();
    database.two_view_geometries[pair_id] = geometry;
  }
  return database;
}

void ExpectSameMatches(const std::vector<FeatureMatch>& a, const std::vector<FeatureMatch>& b,
                       const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].point2D_idx1, b[i].point2D_idx1) << what << " match " << i;
    EXPECT_EQ(a[i].point2D_idx2, b[i].point2D_idx2) << what << " match " << i;
  }
}

void ExpectSameQuaternion(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  EXPECT_EQ(a.coeffs(), b.coeffs());
}

// Field by field, exactly: the database stores every value bit for bit.
void ExpectSameDatabase(const FeatureDatabase& expected, const FeatureDatabase& actual) {
  ASSERT_EQ(expected.cameras.size(), actual.cameras.size());
  for (const auto& [id, camera] : expected.cameras) {
    const Camera& other = actual.cameras.at(id);
    EXPECT_EQ(camera.camera_id, other.camera_id);
    EXPECT_EQ(camera.model, other.model) << "camera " << id;
    EXPECT_EQ(camera.width, other.width);
    EXPECT_EQ(camera.height, other.height);
    EXPECT_EQ(camera.params, other.params) << "camera " << id;
    EXPECT_EQ(camera.has_prior_focal_length, other.has_prior_focal_length);
  }
  ASSERT_EQ(expected.images.size(), actual.images.size());
  for (const auto& [id, image] : expected.images) {
    const Image& other = actual.images.at(id);
    EXPECT_EQ(image.image_id, other.image_id);
    EXPECT_EQ(image.name, other.name);
    EXPECT_EQ(image.camera_id, other.camera_id);
    ASSERT_EQ(image.prior_rotation.has_value(), other.prior_rotation.has_value()) << image.name;
    if (image.prior_rotation) ExpectSameQuaternion(*image.prior_rotation, *other.prior_rotation);
    ASSERT_EQ(image.prior_translation.has_value(), other.prior_translation.has_value());
    if (image.prior_translation) EXPECT_EQ(*image.prior_translation, *other.prior_translation);
  }
  ASSERT_EQ(expected.keypoints.size(), actual.keypoints.size());
  for (const auto& [id, keypoints] : expected.keypoints) {
    EXPECT_EQ(keypoints.num_cols, actual.keypoints.at(id).num_cols) << "image " << id;
    EXPECT_EQ(keypoints.data, actual.keypoints.at(id).data) << "image " << id;
  }
  ASSERT_EQ(expected.descriptors.size(), actual.descriptors.size());
  for (const auto& [id, descriptors] : expected.descriptors) {
    EXPECT_EQ(descriptors.num_cols, actual.descriptors.at(id).num_cols);
    EXPECT_EQ(descriptors.data, actual.descriptors.at(id).data) << "image " << id;
  }
  ASSERT_EQ(expected.matches.size(), actual.matches.size());
  for (const auto& [pair_id, matches] : expected.matches) {
    ExpectSameMatches(matches, actual.matches.at(pair_id), "pair " + std::to_string(pair_id));
  }
  ASSERT_EQ(expected.two_view_geometries.size(), actual.two_view_geometries.size());
  for (const auto& [pair_id, geometry] : expected.two_view_geometries) {
    const TwoViewGeometry& other = actual.two_view_geometries.at(pair_id);
    EXPECT_EQ(geometry.image_id1, other.image_id1);
    EXPECT_EQ(geometry.image_id2, other.image_id2);
    EXPECT_EQ(geometry.config, other.config) << "pair " << pair_id;
    ExpectSameMatches(geometry.inlier_matches, other.inlier_matches,
                      "geometry " + std::to_string(pair_id));
    EXPECT_EQ(geometry.F, other.F) << "pair " << pair_id;
    EXPECT_EQ(geometry.E, other.E);
    EXPECT_EQ(geometry.H, other.H);
    ExpectSameQuaternion(geometry.cam2_from_cam1.rotation, other.cam2_from_cam1.rotation);
    EXPECT_EQ(geometry.cam2_from_cam1.translation, other.cam2_from_cam1.translation);
  }
}

DatabaseReadOptions ReadEverything() {
  DatabaseReadOptions options;
  options.read_descriptors = true;
  options.read_matches = true;
  return options;
}

// Runs SQL on a database file through SQLite (not through the reader under test).
void ExecuteSql(const std::string& path, const std::string& sql) {
  sqlite::Connection db(path, sqlite::Connection::Create(), path);
  db.Execute(sql);
}

// SQL blob literal X'..' of raw bytes.
std::string BlobLiteral(const void* data, size_t size) {
  static const char* kHex = "0123456789ABCDEF";
  std::string literal = "X'";
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) {
    literal += kHex[bytes[i] >> 4];
    literal += kHex[bytes[i] & 15];
  }
  return literal + "'";
}

std::set<std::string> FolderListing(const std::string& folder) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) {
    names.insert(entry.path().filename().string());
  }
  return names;
}

// Reading `path` (and copying it with the writer) fails with an InputError that names the file
// and every one of `items`; the broken file is untouched and nothing new appears anywhere.
void ExpectReadFails(const std::string& path, const std::vector<std::string>& items) {
  const std::string folder = fs::path(path).parent_path().string();
  const std::set<std::string> listing_before = FolderListing(folder);
  const std::string bytes_before = fs::exists(path) ? test::ReadFileBytes(path) : "";
  TempDir out;
  const std::string copy = out / "copy.db";
  try {
    WriteColmapDatabase(ReadColmapDatabase(path, ReadEverything()), copy);
    ADD_FAILURE() << "reading " << path << " did not fail";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_EQ(error.source(), path);
    EXPECT_EQ(message.rfind(path, 0), 0u) << message;
    for (const std::string& item : items) {
      EXPECT_NE(message.find(item), std::string::npos)
          << "message does not name '" << item << "': " << message;
    }
  }
  EXPECT_FALSE(fs::exists(copy));
  EXPECT_TRUE(fs::is_empty(out.path()));
  EXPECT_EQ(FolderListing(folder), listing_before);
  if (fs::exists(path))
    EXPECT_EQ(test::ReadFileBytes(path), bytes_before) << "the reader changed the file";
}

// A good small database at dir/name, then broken with `sql`.
std::string WriteBrokenDatabase(const TempDir& dir, const std::string& sql) {
  const std::string path = dir / "broken.db";
  WriteColmapDatabase(MakeSmallDatabase(), path);
  ExecuteSql(path, sql);
  return path;
}

// The names of the registered images of a COLMAP model folder, via `colmap model_converter`.
std::set<std::string> RegisteredImageNames(const std::string& model, const std::string& scratch) {
  fs::create_directories(scratch);
  const test::CommandResult converted =
      test::RunCommand("colmap model_converter --input_path '" + model + "' --output_path '" +
                       scratch + "' --output_type TXT");
  EXPECT_EQ(converted.exit_code, 0) << converted.output;
  std::ifstream file(scratch + "/images.txt");
  std::vector<std::string> lines;
  for (std::string line; std::getline(file, line);) {
    if (line.empty() || line[0] != '#') lines.push_back(line);
  }
  // Two lines per image: "IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME", then its points (an
  // empty line when it has none, hence empty lines are kept above).
  std::set<std::string> names;
  for (size_t i = 0; i < lines.size(); i += 2) {
    std::istringstream fields(lines[i]);
    std::string field, name;
    for (int k = 0; k < 10 && fields >> field; ++k) name = field;
    names.insert(name);
  }
  return names;
}

// ---------------------------------------------------------------------------------------------
// Round trips and layout.

TEST(ColmapDatabase, RoundTripPreservesEverything) {
  const FeatureDatabase database = MakeFullDatabase();
  TempDir dir;
  const std::string path = dir / "db.db";
  WriteColmapDatabase(database, path);
  // Only the database itself is left: no staging file, no journal.
  EXPECT_EQ(FolderListing(dir.path()), std::set<std::string>{"db.db"});
  ExpectSameDatabase(database, ReadColmapDatabase(path, ReadEverything()));

  // Writing over an existing database replaces it.
  FeatureDatabase smaller = MakeSmallDatabase();
  WriteColmapDatabase(smaller, path);
  ExpectSameDatabase(smaller, ReadColmapDatabase(path, ReadEverything()));
}

// Another process holding the database's lock for a moment (a writer; the last reader of a WAL
// database checkpointing it as it closes) makes a read wait, not fail: two mapper runs on one
// database must both succeed.
TEST(ColmapDatabase, ReadWaitsForAnotherConnectionsLock) {
  const FeatureDatabase database = MakeSmallDatabase();
  TempDir dir;
  const std::string path = dir / "db.db";
  WriteColmapDatabase(database, path);
  sqlite::Connection holder(path, sqlite::Connection::OpenExisting(), path);
  holder.Execute("PRAGMA journal_mode = DELETE");  // so that an exclusive lock shuts out readers
  holder.Execute("BEGIN EXCLUSIVE TRANSACTION");
  holder.Execute("UPDATE images SET name = name");
  std::thread release([&holder] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    holder.Execute("COMMIT");
  });
  FeatureDatabase read;
  EXPECT_NO_THROW(read = ReadColmapDatabase(path, ReadEverything()));
  release.join();
  ExpectSameDatabase(database, read);
}

// ramap's descriptor ratios live in an extra table, written only when there are some, read back
// bit for bit, and kept in match order when a reversed geometry is inverted before storing.
TEST(ColmapDatabase, DescriptorRatiosRoundTripInTheirOwnTable) {
  FeatureDatabase database = MakeSmallDatabase();
  TwoViewGeometry& geometry = database.two_view_geometries.at(ImagePairToPairId(1, 2));
  for (size_t k = 0; k < geometry.inlier_matches.size(); ++k) {
    geometry.inlier_ratios.push_back(0.3f + 0.01f * k);
  }
  TempDir dir;
  WriteColmapDatabase(database, dir / "ratios.db");
  const FeatureDatabase read = ReadColmapDatabase(dir / "ratios.db");
  EXPECT_EQ(read.two_view_geometries.at(ImagePairToPairId(1, 2)).inlier_ratios,
            geometry.inlier_ratios);
  EXPECT_TRUE(read.two_view_geometries.at(ImagePairToPairId(2, 3)).inlier_ratios.empty());
  const test::CommandResult tables = test::RunCommand(
      "sqlite3 '" + dir / "ratios.db" + "' \"SELECT count(*) FROM ramap_match_confidence\"");
  EXPECT_EQ(tables.output, "1\n");

  // Ratios that do not match the inliers are refused by the writer and the reader.
  FeatureDatabase short_ratios = database;
  short_ratios.two_view_geometries.at(ImagePairToPairId(1, 2)).inlier_ratios.pop_back();
  EXPECT_THROW(WriteColmapDatabase(short_ratios, dir / "bad.db"), InputError);
  EXPECT_FALSE(fs::exists(dir / "bad.db"));
  ExecuteSql(dir / "ratios.db", "UPDATE ramap_match_confidence SET rows = 3");
  test::ExpectInputError([&] { ReadColmapDatabase(dir / "ratios.db"); },
                         {"ramap_match_confidence"});
}

TEST(ColmapDatabase, ReadOptionsSkipDescriptorsAndMatches) {
  const FeatureDatabase database = MakeFullDatabase();
  TempDir dir;
  WriteColmapDatabase(database, dir / "db.db");
  DatabaseReadOptions options;
  options.read_descriptors = false;
  options.read_matches = false;
  const FeatureDatabase read = ReadColmapDatabase(dir / "db.db", options);
  EXPECT_TRUE(read.descriptors.empty());
  EXPECT_TRUE(read.matches.empty());
  EXPECT_EQ(read.two_view_geometries.size(), database.two_view_geometries.size());
  EXPECT_EQ(read.keypoints.size(), database.keypoints.size());
}

TEST(ColmapDatabase, StoresMatricesRowMajorAndPoseAsWxyz) {
  FeatureDatabase database = MakeSmallDatabase();
  TwoViewGeometry& geometry = database.two_view_geometries.begin()->second;
  geometry.F << 1, 2, 3, 4, 5, 6, 7, 8, 9;
  geometry.cam2_from_cam1 =
      Rigid3d(Eigen::Quaterniond(0.5, 0.5, -0.5, 0.5), Eigen::Vector3d(10, 20, 30));
  TempDir dir;
  const std::string path = dir / "db.db";
  WriteColmapDatabase(database, path);
  // Decode the raw blobs with SQL only: the row-major F reads 1..9 in order.
  const test::CommandResult dump = test::RunCommand(
      "sqlite3 '" + path + "' \"SELECT hex(F), hex(qvec), hex(tvec) FROM two_view_geometries " +
      "WHERE pair_id = " + std::to_string(database.two_view_geometries.begin()->first) + "\"");
  ASSERT_EQ(dump.exit_code, 0) << dump.output;
  const double f_row_major[9] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  const double qvec[4] = {0.5, 0.5, -0.5, 0.5};
  const double tvec[3] = {10, 20, 30};
  const auto Hex = [](const void* data, size_t size) {
    const std::string literal = BlobLiteral(data, size);
    return literal.substr(2, literal.size() - 3);
  };
  EXPECT_EQ(dump.output, Hex(f_row_major, sizeof(f_row_major)) + "|" + Hex(qvec, sizeof(qvec)) +
                             "|" + Hex(tvec, sizeof(tvec)) + "\n");
}

TEST(ColmapDatabase, GeometryGivenInReverseOrderIsInvertedBeforeStoring) {
  FeatureDatabase database = MakeSmallDatabase();
  const uint64_t pair_id = ImagePairToPairId(2, 3);
  const TwoViewGeometry forward = database.two_view_geometries.at(pair_id);
  TwoViewGeometry backward = InvertTwoViewGeometry(forward);  // image 3 -> image 2
  backward.F << 1, 2, 3, 4, 5, 6, 7, 8, 10;
  backward.H << 2, 0, 1, 0, 3, 0, 0, 1, 1;
  backward.cam2_from_cam1 =
      Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY())),
              Eigen::Vector3d(1, -2, 0.5));
  ASSERT_EQ(backward.image_id1, 3u);
  database.two_view_geometries[pair_id] = backward;

  TempDir dir;
  WriteColmapDatabase(database, dir / "db.db");
  const TwoViewGeometry stored = ReadColmapDatabase(dir / "db.db").two_view_geometries.at(pair_id);
  EXPECT_EQ(stored.image_id1, 2u);
  EXPECT_EQ(stored.image_id2, 3u);
  ExpectSameMatches(forward.inlier_matches, stored.inlier_matches, "inliers");
  EXPECT_EQ(stored.F, backward.F.transpose());
  EXPECT_TRUE(stored.H.isApprox(backward.H.inverse(), 1e-14));
  // The stored pose maps camera 2 (image 2) into camera 3: the inverse of the given one.
  const Rigid3d round = backward.cam2_from_cam1 * stored.cam2_from_cam1;
  EXPECT_LT(round.translation.norm(), 1e-12);
  EXPECT_LT(round.rotation.angularDistance(Eigen::Quaterniond::Identity()), 1e-12);
}

TEST(ColmapDatabase, OldDatabaseWithoutMatricesOrPoseReadsAsZeroAndIdentity) {
  TempDir dir;
  const std::string path = WriteBrokenDatabase(
      dir,
      "UPDATE two_view_geometries SET F = NULL, E = X'', H = NULL, qvec = NULL, tvec = NULL;"
      "UPDATE images SET prior_qw = 1, prior_qx = 0, prior_qy = 0, prior_qz = NULL, "
      "prior_tx = 1, prior_ty = 2, prior_tz = 3 WHERE image_id = 2;");
  const FeatureDatabase database = ReadColmapDatabase(path);
  ASSERT_EQ(database.two_view_geometries.size(), 2u);
  for (const auto& [pair_id, geometry] : database.two_view_geometries) {
    EXPECT_TRUE(geometry.F.isZero(0));
    EXPECT_TRUE(geometry.E.isZero(0));
    EXPECT_TRUE(geometry.H.isZero(0));
    ExpectSameQuaternion(geometry.cam2_from_cam1.rotation, Eigen::Quaterniond::Identity());
    EXPECT_TRUE(geometry.cam2_from_cam1.translation.isZero(0));
    EXPECT_EQ(geometry.inlier_matches.size(), 20u);
  }
  // A prior with one NULL component is absent; the complete translation prior is kept.
  EXPECT_FALSE(database.images.at(2).prior_rotation.has_value());
  ASSERT_TRUE(database.images.at(2).prior_translation.has_value());
  EXPECT_EQ(*database.images.at(2).prior_translation, Eigen::Vector3d(1, 2, 3));
}

TEST(ColmapDatabase, WriterRejectsInconsistentContentsAndWritesNothing) {
  TempDir dir;
  const std::string path = dir / "db.db";
  {
    FeatureDatabase database = MakeSmallDatabase();
    TwoViewGeometry geometry = database.two_view_geometries.begin()->second;
    database.two_view_geometries[ImagePairToPairId(1, 3)] = geometry;  // key of another pair
    test::ExpectInputError([&] { WriteColmapDatabase(database, path); }, {"pair_id"});
  }
  {
    FeatureDatabase database = MakeSmallDatabase();
    database.matches.begin()->second[4].point2D_idx2 = 40;  // image 2 has 40 keypoints
    test::ExpectInputError([&] { WriteColmapDatabase(database, path); }, {"'view2.jpg'"});
  }
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

// ---------------------------------------------------------------------------------------------
// With COLMAP.

TEST(ColmapDatabase, WritesExactlyColmapsSchema) {
  RAMAP_REQUIRE_COLMAP();
  TempDir dir;
  const test::CommandResult created =
      test::RunCommand("colmap database_creator --database_path '" + dir / "colmap.db" + "'");
  ASSERT_EQ(created.exit_code, 0) << created.output;
  WriteColmapDatabase(FeatureDatabase(), dir / "ramap.db");
  const std::string query =
      "\"SELECT type, name, tbl_name, quote(sql) FROM sqlite_master ORDER BY name; "
      "PRAGMA user_version; PRAGMA journal_mode;\"";
  const test::CommandResult colmap =
      test::RunCommand("sqlite3 '" + dir / "colmap.db" + "' " + query);
  const test::CommandResult ramap = test::RunCommand("sqlite3 '" + dir / "ramap.db" + "' " + query);
  ASSERT_EQ(colmap.exit_code, 0) << colmap.output;
  ASSERT_EQ(ramap.exit_code, 0) << ramap.output;
  EXPECT_NE(colmap.output.find("two_view_geometries"), std::string::npos);
  EXPECT_EQ(ramap.output, colmap.output);
}

TEST(ColmapDatabase, ReadsDatabaseMadeByColmapFromRealImages) {
  RAMAP_REQUIRE_COLMAP();
  RAMAP_REQUIRE_SHARED_DATA(images, "strecha/Herz-Jesus-P8/images");
  const std::string path = test::CachedColmapDatabase(test::HerzJesusFourImages(images));
  ASSERT_FALSE(path.empty());
  const FeatureDatabase database = ReadColmapDatabase(path, ReadEverything());

  // The same counts, computed by the sqlite3 shell from the rows' size columns.
  const test::CommandResult counts = test::RunCommand(
      "sqlite3 '" + path +
      "' \"SELECT (SELECT count(*) FROM cameras), (SELECT count(*) FROM images), "
      "(SELECT sum(rows) FROM keypoints), (SELECT sum(rows) FROM descriptors), "
      "(SELECT count(*) FROM matches WHERE rows > 0), (SELECT sum(rows) FROM matches), "
      "(SELECT count(*) FROM two_view_geometries WHERE config = 2), "
      "(SELECT sum(rows) FROM two_view_geometries)\"");
  ASSERT_EQ(counts.exit_code, 0) << counts.output;
  size_t num_keypoints = 0, num_descriptors = 0, num_pairs = 0, num_matches = 0, num_calibrated = 0,
         num_inliers = 0;
  for (const auto& [id, keypoints] : database.keypoints) num_keypoints += keypoints.size();
  for (const auto& [id, descriptors] : database.descriptors) {
    num_descriptors += descriptors.size();
    EXPECT_EQ(descriptors.num_cols, 128);
  }
  for (const auto& [pair_id, matches] : database.matches) {
    num_pairs += matches.empty() ? 0 : 1;
    num_matches += matches.size();
  }
  for (const auto& [pair_id, geometry] : database.two_view_geometries) {
    num_calibrated += geometry.config == TwoViewConfig::kCalibrated ? 1 : 0;
    num_inliers += geometry.inlier_matches.size();
  }
  const std::string ours =
      std::to_string(database.cameras.size()) + "|" + std::to_string(database.images.size()) + "|" +
      std::to_string(num_keypoints) + "|" + std::to_string(num_descriptors) + "|" +
      std::to_string(num_pairs) + "|" + std::to_string(num_matches) + "|" +
      std::to_string(num_calibrated) + "|" + std::to_string(num_inliers) + "\n";
  EXPECT_EQ(ours, counts.output);
  EXPECT_EQ(database.images.size(), 4u);
  EXPECT_GT(num_keypoints, 1000u);
  EXPECT_GT(num_inliers, 100u);

  // COLMAP stores intrinsics at full resolution, as given.
  ASSERT_EQ(database.cameras.size(), 1u);
  const Camera& camera = database.cameras.begin()->second;
  EXPECT_EQ(camera.model, CameraModel::kPinhole);
  EXPECT_EQ(camera.params, (std::vector<double>{2759.48, 2764.16, 1520.69, 1006.81}));
  std::set<std::string> names;
  for (const auto& [id, image] : database.images) {
    names.insert(image.name);
    EXPECT_FALSE(image.prior_rotation.has_value());  // COLMAP writes no priors here
    // Keypoints are in the full-resolution pixel frame.
    const Keypoints& keypoints = database.keypoints.at(id);
    for (size_t k = 0; k < keypoints.size(); ++k) {
      const Eigen::Vector2d xy = keypoints.xy(k);
      ASSERT_TRUE(xy.x() >= 0 && xy.x() <= camera.width && xy.y() >= 0 && xy.y() <= camera.height)
          << image.name << " keypoint " << k;
    }
  }
  EXPECT_EQ(names, (std::set<std::string>{"0000.jpg", "0001.jpg", "0002.jpg", "0003.jpg"}));
}

TEST(ColmapDatabase, ColmapMapperAcceptsDatabaseWrittenByRamap) {
  RAMAP_REQUIRE_COLMAP();
  RAMAP_REQUIRE_SHARED_DATA(images, "strecha/Herz-Jesus-P8/images");
  const test::ColmapRun run = test::HerzJesusFourImages(images);
  const std::string reference_model = test::CachedColmapModel(run);
  ASSERT_FALSE(reference_model.empty());
  const std::string colmap_database = test::CachedColmapDatabase(run);
  const std::string image_path = fs::path(colmap_database).parent_path().string() + "/images";

  TempDir dir;
  const std::string copy = dir / "ramap.db";
  const FeatureDatabase original = ReadColmapDatabase(colmap_database, ReadEverything());
  WriteColmapDatabase(original, copy);
  ExpectSameDatabase(original, ReadColmapDatabase(copy, ReadEverything()));

  fs::create_directories(dir / "sparse");
  const test::CommandResult mapper =
      test::RunCommand("colmap mapper --database_path '" + copy + "' --image_path '" + image_path +
                       "' --output_path '" + dir / "sparse" +
                       "' --Mapper.num_threads 2 --Mapper.ba_refine_focal_length 0"
                       " --Mapper.ba_refine_principal_point 0 --Mapper.ba_refine_extra_params 0");
  ASSERT_EQ(mapper.exit_code, 0) << mapper.output;
  ASSERT_TRUE(fs::exists(dir / "sparse/0/images.bin")) << mapper.output;
  const std::set<std::string> ours = RegisteredImageNames(dir / "sparse/0", dir / "ours_txt");
  const std::set<std::string> reference = RegisteredImageNames(reference_model, dir / "ref_txt");
  EXPECT_EQ(ours.size(), 4u);
  EXPECT_EQ(ours, reference);
}

// ---------------------------------------------------------------------------------------------
// Bad input: one defect each.

TEST(ColmapDatabaseBadInput, MissingFile) {
  TempDir dir;
  ExpectReadFails(dir / "nothing_here.db", {"no such file"});
}

TEST(ColmapDatabaseBadInput, TextFileIsNotADatabase) {
  TempDir dir;
  const std::string path = dir / "notes.db";
  std::ofstream(path) << "# this is a list of images, not a database\n0000.jpg\n0001.jpg\n";
  ExpectReadFails(path, {"not a readable SQLite database"});
}

TEST(ColmapDatabaseBadInput, EmptySqliteFileHasNoTables) {
  TempDir dir;
  const std::string path = dir / "empty.db";
  ExecuteSql(path, "PRAGMA user_version = 1");  // a valid SQLite file without tables
  ASSERT_TRUE(fs::exists(path));
  ExpectReadFails(path, {"missing table 'cameras'"});
}

TEST(ColmapDatabaseBadInput, TableMissingAColumn) {
  TempDir dir;
  const std::string path =
      WriteBrokenDatabase(dir, "ALTER TABLE two_view_geometries DROP COLUMN qvec");
  ExpectReadFails(path, {"two_view_geometries", "missing column 'qvec'", "older than 3.8"});
}

TEST(ColmapDatabaseBadInput, TruncatedKeypointBlob) {
  TempDir dir;
  const std::string path = WriteBrokenDatabase(
      dir, "UPDATE keypoints SET data = substr(data, 1, length(data) - 4) WHERE image_id = 2");
  ExpectReadFails(path, {"keypoints of image 2 'view2.jpg'", "truncated"});
}

TEST(ColmapDatabaseBadInput, MatchIndexOutOfRange) {
  TempDir dir;
  // The first match of pair (2, 3) points at keypoint 40 of image 3, which has 40.
  const uint32_t bad_match[2] = {0, 40};
  const std::string path = WriteBrokenDatabase(
      dir, "UPDATE matches SET data = " + BlobLiteral(bad_match, sizeof(bad_match)) +
               " || substr(data, 9) WHERE pair_id = " + std::to_string(ImagePairToPairId(2, 3)));
  ExpectReadFails(path, {"matches of pair (image 2 'view2.jpg', image 3 'view3.jpg')",
                         "keypoint 40 of image 3 'view3.jpg', which has 40 keypoints"});
}

TEST(ColmapDatabaseBadInput, NaNFocalLength) {
  TempDir dir;
  const double params[4] = {std::numeric_limits<double>::quiet_NaN(), 510, 320, 240};
  const std::string path = WriteBrokenDatabase(
      dir, "UPDATE cameras SET params = " + BlobLiteral(params, sizeof(params)));
  ExpectReadFails(path, {"camera 1 (PINHOLE)", "fx (focal length)", "nan"});
}

TEST(ColmapDatabaseBadInput, UnknownCameraModelId) {
  TempDir dir;
  const std::string path = WriteBrokenDatabase(dir, "UPDATE cameras SET model = 42");
  ExpectReadFails(path, {"camera 1", "unknown camera model id 42"});
}

TEST(ColmapDatabaseBadInput, PairOfUnknownImage) {
  TempDir dir;
  const std::string path = WriteBrokenDatabase(
      dir, "UPDATE two_view_geometries SET pair_id = " + std::to_string(ImagePairToPairId(2, 9)) +
               " WHERE pair_id = " + std::to_string(ImagePairToPairId(2, 3)));
  ExpectReadFails(path, {"two_view_geometries", "image id 9", "not in table images"});
}

// ---------------------------------------------------------------------------------------------
// The database_info command.

TEST(ColmapDatabaseCli, DatabaseInfoPrintsCounts) {
  TempDir dir;
  WriteColmapDatabase(MakeSmallDatabase(), dir / "db.db");
  const test::CommandResult result = test::RunCommand(
      "'" + test::RamapBinary() + "' database_info --database_path '" + dir / "db.db" + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("cameras:                 1\n"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("images:                  3\n"), std::string::npos);
  EXPECT_NE(result.output.find("keypoints:               120 in 3 images"), std::string::npos);
  EXPECT_NE(result.output.find("pairs with matches:      2 (60 matches)"), std::string::npos);
  EXPECT_NE(result.output.find("verified pairs:          2 (40 inlier matches)"),
            std::string::npos);
  EXPECT_NE(result.output.find("CALIBRATED: 2"), std::string::npos);
  EXPECT_NE(result.output.find("pose priors:         0 images"), std::string::npos);
  EXPECT_NE(result.output.find("descriptor ratios:       0 verified pairs"), std::string::npos);
}

TEST(ColmapDatabaseCli, DatabaseInfoFailsOnBrokenDatabase) {
  TempDir dir;
  const std::string path = WriteBrokenDatabase(
      dir, "UPDATE keypoints SET data = substr(data, 1, 100) WHERE image_id = 3");
  const test::CommandResult result = test::RunCommand(
      "'" + test::RamapBinary() + "' database_info --database_path '" + path + "'");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find(path + ": keypoints of image 3 'view3.jpg'"), std::string::npos)
      << result.output;
}

// ---------------------------------------------------------------------------------------------
// Speed.

TEST(ColmapDatabase, ReadsTwoHundredImagesAndFiveThousandPairsQuickly) {
  std::mt19937 rng(11);
  FeatureDatabase database;
  Camera camera;
  camera.camera_id = 1;
  camera.model = CameraModel::kSimpleRadial;
  camera.width = 1920;
  camera.height = 1080;
  camera.params = {1500, 960, 540, 0.01};
  database.cameras[1] = camera;
  const uint32_t kNumImages = 200;
  const size_t kNumKeypoints = 2000;
  for (uint32_t id = 1; id <= kNumImages; ++id) {
    Image image;
    image.image_id = id;
    image.name = std::to_string(id) + ".jpg";
    image.camera_id = 1;
    database.images[id] = image;
    database.keypoints[id] = RandomKeypoints(rng, kNumKeypoints, 6);
  }
  // Each image with its next 25: 200 * 25 = 5000 pairs (wrapping around).
  for (uint32_t id = 1; id <= kNumImages; ++id) {
    for (uint32_t step = 1; step <= 25; ++step) {
      const uint32_t other = (id - 1 + step) % kNumImages + 1;
      const uint64_t pair_id = ImagePairToPairId(id, other);
      database.matches[pair_id] = RandomMatches(rng, 300, kNumKeypoints, kNumKeypoints);
      TwoViewGeometry geometry;
      geometry.image_id1 = std::min(id, other);
      geometry.image_id2 = std::max(id, other);
      geometry.config = TwoViewConfig::kCalibrated;
      geometry.inlier_matches = RandomMatches(rng, 200, kNumKeypoints, kNumKeypoints);
      database.two_view_geometries[pair_id] = geometry;
    }
  }
  ASSERT_EQ(database.two_view_geometries.size(), 5000u);
  TempDir dir;
  Timer write_timer;
  WriteColmapDatabase(database, dir / "big.db");
  const double write_seconds = write_timer.ElapsedSeconds();
  Timer read_timer;
  const FeatureDatabase read = ReadColmapDatabase(dir / "big.db");
  const double read_seconds = read_timer.ElapsedSeconds();
  RecordProperty("write_seconds", std::to_string(write_seconds));
  RecordProperty("read_seconds", std::to_string(read_seconds));
  std::cout << "200 images, 5000 pairs: write " << write_seconds << " s, read " << read_seconds
            << " s\n";
  EXPECT_EQ(read.two_view_geometries.size(), 5000u);
  EXPECT_EQ(read.matches.size(), 5000u);
  // Well under a second on an idle machine; the bound leaves room for a busy shared one.
  EXPECT_LT(read_seconds, 2.0);
}

}  // namespace
}  // namespace ramap
