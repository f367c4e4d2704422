// Bad input against the built binary, as a hostile but realistic user gives it. Every case asserts
// the exit code, that the message names the file or option at fault, that nothing crashed, and
// that the user's files are as they were: the tree is compared before and after.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <sstream>

#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "ramap/io/sqlite.h"
#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

std::string Q(const std::string& path) { return "'" + path + "'"; }

// Every entry under `root`: its kind, size and contents (files), by relative path.
std::map<std::string, std::string> Snapshot(const std::string& root) {
  std::map<std::string, std::string> tree;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(root)) {
    const std::string relative = fs::relative(entry.path(), root).string();
    if (entry.is_directory()) {
      tree[relative] = "folder";
      continue;
    }
    std::ifstream in(entry.path(), std::ios::binary);
    std::ostringstream contents;
    contents << in.rdbuf();
    tree[relative] = "file:" + std::to_string(contents.str().size()) + ":" +
                     std::to_string(std::hash<std::string>()(contents.str()));
  }
  return tree;
}

// A synthetic scene (database, ground truth) and a mapper output beside it, made once and copied
// into a fresh folder for every test so that no test sees another's leftovers.
class BadInput : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = std::make_unique<test::TempDir>();
    const test::CommandResult synthesize = test::RunCommand(
        test::RamapCommand() + "synthesize --output_path " + Q(*scene_ / "scene") +
        " --Synthetic.path circle --Synthetic.num_images 8 --Synthetic.num_points 600"
        " --Synthetic.pixel_noise 0.5 --Synthetic.seed 3");
    ASSERT_EQ(synthesize.exit_code, 0) << synthesize.output;
    const test::CommandResult mapper = test::RunCommand(
        test::RamapCommand() + "mapper --database_path " + Q(*scene_ / "scene/database.db") +
        " --output_path " + Q(*scene_ / "scene/sparse"));
    ASSERT_EQ(mapper.exit_code, 0) << mapper.output;
    // A few textured images for the image commands.
    fs::create_directories(*scene_ / "scene/images");
    std::mt19937 random(5);
    for (int k = 0; k < 2; ++k) {
      cv::Mat image(240, 320, CV_8U);
      for (int r = 0; r < image.rows; ++r) {
        for (int c = 0; c < image.cols; ++c) image.at<uint8_t>(r, c) = random() % 256;
      }
      cv::imwrite(*scene_ / ("scene/images/noise" + std::to_string(k) + ".png"), image);
    }
  }
  static void TearDownTestSuite() { scene_.reset(); }

  void SetUp() override {
    fs::copy(*scene_ / "scene", work_.path(), fs::copy_options::recursive);
    before_ = Snapshot(work_.path());
  }

  std::string W(const std::string& name) const { return work_ / name; }

  // Runs `arguments` in the work folder; expects a clean refusal whose message holds `named`, and
  // an unchanged tree.
  void ExpectRefused(const std::string& arguments, const std::string& named) {
    const test::CommandResult result =
        test::RunCommand("cd " + Q(work_.path()) + " && " + test::RamapCommand() + arguments);
    EXPECT_NE(result.exit_code, 0) << result.output;
    EXPECT_LT(result.exit_code, 128) << "killed by a signal:\n" << result.output;
    EXPECT_EQ(result.output.find("internal error"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("error:"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find(named), std::string::npos)
        << "the message should name '" << named << "':\n"
        << result.output;
    EXPECT_EQ(Snapshot(work_.path()), before_) << "files changed by: " << arguments;
  }

  static std::unique_ptr<test::TempDir> scene_;
  test::TempDir work_;
  std::map<std::string, std::string> before_;
};

std::unique_ptr<test::TempDir> BadInput::scene_;

// --- Outputs that would replace a folder, the working directory or an input ---

TEST_F(BadInput, FileOutputIsTheWorkingDirectory) {
  ExpectRefused("relative_poses --database_path database.db --output_path .", "--output_path");
  ExpectRefused("relative_poses --database_path database.db --output_path ./", "--output_path");
}

TEST_F(BadInput, FileOutputIsAnExistingFolder) {
  ExpectRefused("relative_poses --database_path database.db --output_path sparse",
                "--output_path sparse");
  ExpectRefused("rotation_averager --database_path database.db --output_path sparse/0",
                "--output_path sparse/0");
  ExpectRefused(
      "evaluate --model_path sparse/0 --ground_truth ground_truth"
      " --ground_truth_format colmap --output_path sparse",
      "--output_path sparse");
}

// An output under a regular file is refused before any work, naming the file in the way
// (it was "internal error: filesystem error" after the whole run).
TEST_F(BadInput, OutputUnderAFile) {
  ExpectRefused("mapper --database_path database.db --output_path ground_truth.txt/out",
                "ground_truth.txt is a file, not a folder");
  ExpectRefused(
      "relative_poses --database_path database.db --output_path ground_truth.txt/a/edges.txt",
      "ground_truth.txt is a file, not a folder");
  ExpectRefused(
      "evaluate --model_path sparse/0 --ground_truth ground_truth.txt --ground_truth_format tum "
      "--output_path ground_truth.txt/evaluation.json",
      "--output_path ground_truth.txt/evaluation.json");
}

// A folder the user cannot write into is named before any work (root writes anywhere: skipped).
TEST_F(BadInput, OutputInAnUnwritableFolder) {
  if (::geteuid() == 0) GTEST_SKIP() << "running as root, every folder is writable";
  fs::create_directories(W("locked"));
  fs::permissions(W("locked"), fs::perms::owner_read | fs::perms::owner_exec);
  before_ = Snapshot(work_.path());
  ExpectRefused("mapper --database_path database.db --output_path locked/out",
                "no permission to create or change files in locked");
  fs::permissions(W("locked"), fs::perms::owner_all);
}

// Where even root may not write (sysfs): named before any work, not a filesystem error after it.
TEST_F(BadInput, OutputWhereNobodyMayWrite) {
  std::error_code ec;
  if (!fs::is_directory("/sys", ec) || fs::create_directory("/sys/ramap-bad-input-test", ec)) {
    fs::remove("/sys/ramap-bad-input-test", ec);
    GTEST_SKIP() << "/sys is missing or writable here";
  }
  ExpectRefused("mapper --database_path database.db --output_path /sys/ramap-out",
                "--output_path /sys/ramap-out: cannot be written: creating files in /sys fails");
  ExpectRefused("relative_poses --database_path database.db --output_path /sys/edges.txt",
                "--output_path /sys/edges.txt: cannot be written");
}

TEST_F(BadInput, FileOutputIsAnInput) {
  ExpectRefused("relative_poses --database_path database.db --output_path database.db",
                "is an input");
  ExpectRefused(
      "evaluate --model_path sparse/0 --ground_truth ground_truth"
      " --ground_truth_format colmap --output_path sparse/0/images.bin",
      "is an input");
  ExpectRefused(
      "evaluate --model_path sparse/0 --ground_truth ground_truth.txt"
      " --ground_truth_format tum --output_path ground_truth.txt",
      "is an input");
}

TEST_F(BadInput, DatabaseOverAnImageFolderOrAnExistingDatabase) {
  ExpectRefused("feature_extractor --image_path images --database_path images", "images");
  ExpectRefused("feature_extractor --image_path images --database_path database.db",
                "exists already");
  ExpectRefused("synthesize --output_path .", "exists already");
  ExpectRefused("reconstruct --image_path images --output_path .", "exists already");
}

TEST_F(BadInput, ModelOfTheOtherFormatInTheFolder) {
  ExpectRefused(
      "model_converter --input_path sparse/0 --output_path ground_truth"
      " --output_type TXT",
      "already holds a binary model");
  ExpectRefused("model_converter --input_path sparse/0 --output_path sparse/0 --output_type BIN",
                "is an input");
}

// A model an export cannot express: refused by name, nothing written (the tree is unchanged).
TEST_F(BadInput, ExportOfAModelTheFormatCannotExpress) {
  const Reconstruction model = ReadColmapModel(W("sparse/0"));
  Reconstruction no_images = model;
  no_images.images.clear();
  no_images.points3D.clear();
  WriteColmapModel(no_images, W("empty"));
  // ramap writes no NaN pose: the first image's tx (after the count, the id and the quaternion)
  // made NaN by hand.
  fs::copy(W("sparse/0"), W("nan"));
  {
    std::fstream images(W("nan/images.bin"), std::ios::in | std::ios::out | std::ios::binary);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    images.seekp(sizeof(uint64_t) + sizeof(uint32_t) + 4 * sizeof(double));
    images.write(reinterpret_cast<const char*>(&nan), sizeof(nan));
  }
  Reconstruction fisheye = model;
  fisheye.cameras.begin()->second.model = CameraModel::kFullOpenCV;
  fisheye.cameras.begin()->second.params.resize(12, 0.0);
  WriteColmapModel(fisheye, W("full_opencv"));
  before_ = Snapshot(work_.path());
  for (const std::string type : {"NERFSTUDIO", "TUM"}) {
    ExpectRefused("model_converter --input_path empty --output_path out --output_type " + type,
                  "no image");
  }
  ExpectRefused("model_converter --input_path nan --output_path out --output_type NERFSTUDIO",
                "NaN");
  ExpectRefused("model_converter --input_path nan --output_path out.txt --output_type TUM", "NaN");
  ExpectRefused(
      "model_converter --input_path nan --output_path out.ply --output_type PLY --export_cameras 1",
      "NaN");
  ExpectRefused(
      "model_converter --input_path full_opencv --output_path out --output_type NERFSTUDIO",
      "FULL_OPENCV");
  ExpectRefused("model_converter --input_path sparse/0 --output_path out --output_type VRML",
                "--output_type");
}

TEST_F(BadInput, MapperOutputWithTheUsersFiles) {
  std::ofstream(W("sparse/0/notes.txt")) << "mine";
  before_ = Snapshot(work_.path());
  ExpectRefused("mapper --database_path database.db --output_path sparse", "notes.txt");
  fs::remove(W("sparse/0/notes.txt"));
  // A stale model of an earlier run beside the user's file is not removed either.
  fs::copy(W("sparse/0"), W("sparse/1"), fs::copy_options::recursive);
  std::ofstream(W("sparse/1/notes.txt")) << "mine";
  before_ = Snapshot(work_.path());
  ExpectRefused("mapper --database_path database.db --output_path sparse", "notes.txt");
  // A report.html of the user's own (not ramap's page) is not replaced.
  fs::remove_all(W("sparse/1"));
  std::ofstream(W("sparse/report.html"), std::ios::trunc) << "<html>my own notes</html>";
  before_ = Snapshot(work_.path());
  ExpectRefused("mapper --database_path database.db --output_path sparse", "report.html");
}

TEST_F(BadInput, MapperRerunReplacesOnlyItsOwnOutput) {
  std::ofstream(W("sparse/readme.txt")) << "mine";
  const test::CommandResult result =
      test::RunCommand(test::RamapCommand() + "mapper --database_path " + Q(W("database.db")) +
                       " --output_path " + Q(W("sparse")) + " --output_type TXT");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(fs::exists(W("sparse/readme.txt")));
  EXPECT_TRUE(fs::exists(W("sparse/0/cameras.txt")));
  // The whole model folder was replaced: no binary model shadows the new text one.
  EXPECT_FALSE(fs::exists(W("sparse/0/cameras.bin")));
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(work_.path())) {
    EXPECT_EQ(entry.path().string().find(".ramap-"), std::string::npos) << entry.path();
  }
}

TEST_F(BadInput, CompareOutputWithTheUsersFiles) {
  fs::create_directories(W("report/ramap"));
  std::ofstream(W("report/ramap/keep.txt")) << "mine";
  before_ = Snapshot(work_.path());
  ExpectRefused("compare --database_path database.db --output_path report --colmap_path false",
                "keep.txt");
}

TEST_F(BadInput, MatcherKeepsTablesItDoesNotOwn) {
  const test::CommandResult extract = test::RunCommand(
      test::RamapCommand() + "feature_extractor --image_path " + Q(W("images")) +
      " --database_path " + Q(W("new.db")) + " --ImageReader.camera_params 300,160,120,0");
  ASSERT_EQ(extract.exit_code, 0) << extract.output;
  {
    sqlite::Connection db(W("new.db"), sqlite::Connection::OpenExisting(), "new.db");
    db.Execute("CREATE TABLE user_notes (note TEXT); INSERT INTO user_notes VALUES ('mine');");
  }
  const test::CommandResult match =
      test::RunCommand(test::RamapCommand() + "matcher --database_path " + Q(W("new.db")) +
                       " --Matching.mode exhaustive");
  ASSERT_EQ(match.exit_code, 0) << match.output;
  sqlite::Connection db(W("new.db"), sqlite::Connection::OpenExisting(), "new.db");
  sqlite::Statement row(db, "SELECT note FROM user_notes");
  ASSERT_TRUE(row.Step());
  EXPECT_EQ(row.ColumnText(0), "mine");
}

// --- Crashes ---

TEST_F(BadInput, TinyImageIsSkippedByName) {
  cv::imwrite(W("images/tiny.png"), cv::Mat(1, 1, CV_8U, cv::Scalar(7)));
  const test::CommandResult result =
      test::RunCommand(test::RamapCommand() + "feature_extractor --image_path " + Q(W("images")) +
                       " --database_path " + Q(W("new.db")) + " --FeatureExtraction.type sift");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("tiny.png: too small"), std::string::npos) << result.output;
  // Only tiny images: nothing to write, and said so.
  fs::create_directories(W("tiny"));
  cv::imwrite(W("tiny/a.png"), cv::Mat(1, 40, CV_8U, cv::Scalar(7)));
  before_ = Snapshot(work_.path());
  ExpectRefused("feature_extractor --image_path tiny --database_path tiny.db", "too small");
  ExpectRefused("reconstruct --image_path tiny --output_path out", "too small");
}

TEST_F(BadInput, DescriptorsWithoutTheirKeypoints) {
  const test::CommandResult extract =
      test::RunCommand(test::RamapCommand() + "feature_extractor --image_path " + Q(W("images")) +
                       " --database_path " + Q(W("new.db")));
  ASSERT_EQ(extract.exit_code, 0) << extract.output;
  {
    sqlite::Connection db(W("new.db"), sqlite::Connection::OpenExisting(), "new.db");
    db.Execute("UPDATE keypoints SET rows = 0, data = x'' WHERE image_id = 1");
  }
  before_ = Snapshot(work_.path());
  ExpectRefused("matcher --database_path new.db", "descriptors for 0 keypoints");
}

TEST_F(BadInput, OptionsOutOfRange) {
  const std::string mapper = "mapper --database_path database.db --output_path out ";
  ExpectRefused(mapper + "--RelativePose.grid_cols 50000 --RelativePose.grid_rows 50000",
                "--RelativePose.grid_cols");
  ExpectRefused(mapper + "--RelativePose.max_epipolar_error_px inf",
                "--RelativePose.max_epipolar_error_px");
  ExpectRefused(mapper + "--RelativePose.max_epipolar_error_px nan",
                "--RelativePose.max_epipolar_error_px");
  ExpectRefused(mapper + "--RotationAveraging.alpha_max_deg 270",
                "--RotationAveraging.alpha_max_deg");
  ExpectRefused(mapper + "--Mapper.num_threads 0", "--Mapper.num_threads");
  ExpectRefused(mapper + "--TranslationAveraging.min_triangulation_angle_deg -1",
                "--TranslationAveraging.min_triangulation_angle_deg");
  ExpectRefused(mapper + "--PosePrior.std_x_m 0", "--PosePrior.std_x_m");
  ExpectRefused("matcher --database_path database.db --Matching.max_ratio 2",
                "--Matching.max_ratio");
}

// Each a clear error naming the option, exit 2, nothing written (ExpectRefused checks the tree).
TEST_F(BadInput, EmptyOutputPathIsRefusedBeforeAnyWork) {
  const test::CommandResult result = test::RunCommand(
      "cd " + Q(work_.path()) + " && " + test::RamapCommand() +
      "mapper --database_path database.db --output_path ''");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("--output_path: names no file or folder (the path is empty)"),
            std::string::npos)
      << result.output;
  // Refused at parsing: no stage ran.
  EXPECT_EQ(result.output.find("relative poses"), std::string::npos) << result.output;
  EXPECT_EQ(Snapshot(work_.path()), before_);
  ExpectRefused("reconstruct --image_path images --output_path ''", "--output_path");
  ExpectRefused("synthesize --output_path ''", "--output_path");
}

TEST_F(BadInput, AucThresholdsOutOfRangeNameTheOption) {
  const std::string evaluate =
      "evaluate --model_path sparse/0 --ground_truth ground_truth --ground_truth_format colmap ";
  ExpectRefused(evaluate + "--auc_thresholds -5,0",
                "--auc_thresholds: must be a list of angles in (0, 180] degrees, got -5,0");
  ExpectRefused(evaluate + "--auc_thresholds 3,x", "--auc_thresholds");
  ExpectRefused(evaluate + "--robust_alignment 1", "--robust_alignment_max_error");
}

// Index-matched ground truth (TUM, KITTI) and a list that names no image of the model: said as
// such, not as a count of poses and images.
TEST_F(BadInput, ImageListNamingNoImageOfTheModelNamesTheList) {
  std::ofstream(W("list.txt")) << "a.png\nb.png\n";
  before_ = Snapshot(work_.path());
  for (const std::string format : {"tum", "colmap"}) {
    const std::string truth = format == "tum" ? "ground_truth.txt" : "ground_truth";
    ExpectRefused("evaluate --model_path sparse/0 --ground_truth " + truth +
                      " --ground_truth_format " + format + " --image_list list.txt",
                  "--image_list: none of the 2 images of list.txt (a.png, b.png) is in the model "
                  "sparse/0");
  }
}

TEST_F(BadInput, CompareWithAMissingColmapSaysSoBeforeRunning) {
  ExpectRefused(
      "compare --database_path database.db --output_path report --colmap_path "
      "/nonexistent/colmap",
      "--colmap_path: no such file: /nonexistent/colmap");
  ExpectRefused(
      "compare --database_path database.db --output_path report --colmap_path no_such_colmap",
      "--colmap_path: no program 'no_such_colmap' on the PATH");
}

// --- Silent wrong successes ---

TEST_F(BadInput, DuplicateImageNames) {
  {
    sqlite::Connection db(W("database.db"), sqlite::Connection::OpenExisting(), "database.db");
    // As a database built without COLMAP's UNIQUE constraint would be.
    db.Execute(
        "CREATE TABLE images2 AS SELECT * FROM images; DROP TABLE images;"
        "ALTER TABLE images2 RENAME TO images;"
        "UPDATE images SET name = (SELECT name FROM images WHERE image_id = 1) WHERE image_id = "
        "2;");
  }
  before_ = Snapshot(work_.path());
  ExpectRefused("mapper --database_path database.db --output_path out", "same name");
}

TEST_F(BadInput, GroundTruthOfAnotherScene) {
  std::ofstream(W("other.txt")) << "1 0 0 0 0 0 0 1\n2 1 0 0 0 0 0 1\n";
  before_ = Snapshot(work_.path());
  ExpectRefused(
      "evaluate --model_path sparse/0 --ground_truth ground_truth.txt"
      " --ground_truth_format kitti",
      "ground_truth.txt");
  ExpectRefused(
      "evaluate --model_path sparse/0 --ground_truth other.txt"
      " --ground_truth_format tum --database_path database.db",
      "other.txt");
}

TEST_F(BadInput, ImageListSharingNoName) {
  std::ofstream(W("list.txt")) << "nothing_like_it.png\n";
  before_ = Snapshot(work_.path());
  ExpectRefused("feature_extractor --image_path images --image_list list.txt --database_path n.db",
                "images");
  ExpectRefused(
      "evaluate --model_path sparse/0 --ground_truth ground_truth"
      " --ground_truth_format colmap --image_list list.txt",
      "list.txt");
}

TEST_F(BadInput, CompareFailsWhenColmapFails) {
  const test::CommandResult result = test::RunCommand(
      "cd " + Q(work_.path()) + " && " + test::RamapCommand() +
      "compare --database_path database.db --output_path report --colmap_path false");
  EXPECT_NE(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("COLMAP failed"), std::string::npos) << result.output;
  EXPECT_TRUE(fs::exists(W("report/report.md")));  // the report still says what ran
}

TEST_F(BadInput, AllPairsPanoramic) {
  {
    sqlite::Connection db(W("database.db"), sqlite::Connection::OpenExisting(), "database.db");
    db.Execute("UPDATE two_view_geometries SET config = 5");
  }
  before_ = Snapshot(work_.path());
  ExpectRefused("mapper --database_path database.db --output_path out", "PANORAMIC");
}

TEST_F(BadInput, NameWithBlankRefusedBeforeTheSolve) {
  {
    sqlite::Connection db(W("database.db"), sqlite::Connection::OpenExisting(), "database.db");
    db.Execute("UPDATE images SET name = 'with blank.png' WHERE image_id = 1");
  }
  before_ = Snapshot(work_.path());
  const test::CommandResult result = test::RunCommand(
      "cd " + Q(work_.path()) + " && " + test::RamapCommand() +
      "mapper --database_path database.db --output_path out --output_type TXT --log_level 1");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("database.db: image 1 'with blank.png'"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("asked for by --output_type TXT; --output_type BIN holds it"),
            std::string::npos)
      << result.output;
  EXPECT_EQ(result.output.find("rotation averaging"), std::string::npos) << result.output;
  EXPECT_EQ(Snapshot(work_.path()), before_);
}

TEST_F(BadInput, PairWithEveryKeypointOnOnePixelIsDropped) {
  FeatureDatabase database = ReadColmapDatabase(W("database.db"));
  Keypoints& keypoints = database.keypoints.at(1);
  for (size_t k = 0; k < keypoints.size(); ++k) {
    keypoints.data[k * keypoints.num_cols] = 100.5f;
    keypoints.data[k * keypoints.num_cols + 1] = 100.5f;
  }
  WriteColmapDatabase(database, W("one_pixel.db"));
  const test::CommandResult result =
      test::RunCommand(test::RamapCommand() + "relative_poses --database_path " +
                       Q(W("one_pixel.db")) + " --output_path " + Q(W("edges.txt")));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::ifstream edges(W("edges.txt"));
  const std::string name = database.images.at(1).name;
  for (std::string line; std::getline(edges, line);) {
    EXPECT_EQ(line.find(name + " "), std::string::npos) << "kept: " << line;
  }
}

TEST_F(BadInput, DisconnectedGraphIsNotCalledPruned) {
  ASSERT_EQ(test::RunCommand(test::RamapCommand() + "relative_poses --database_path " +
                             Q(W("database.db")) + " --output_path " + Q(W("edges.txt")))
                .exit_code,
            0);
  // The same edges again under other names: a second component, as consistent as the first.
  std::ifstream in(W("edges.txt"));
  std::ofstream out(W("two_components.txt"));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  for (const std::string& line : lines) out << line << "\n";
  for (const std::string& line : lines) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string name1, name2, rest;
    fields >> name1 >> name2;
    std::getline(fields, rest);
    // The first component is the larger: drop one edge of the copy.
    if (&line == &lines.back()) continue;
    out << "copy_" << name1 << " copy_" << name2 << rest << "\n";
  }
  out.close();
  const test::CommandResult result =
      test::RunCommand(test::RamapCommand() + "rotation_averager --relative_poses " +
                       Q(W("two_components.txt")) + " --output_path " + Q(W("rotations.txt")));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("(0 pruned, "), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("outside the largest connected component"), std::string::npos)
      << result.output;
}

// --- Partial outputs ---

TEST_F(BadInput, FailedReconstructLeavesNothing) {
  // Noise images match nothing: the run fails after extraction and matching.
  ExpectRefused(
      "reconstruct --image_path images --output_path out --ImageReader.camera_params "
      "300,160,120,0",
      "out/database.db");
  EXPECT_FALSE(fs::exists(W("out")));
  // Into an existing folder: the database it created goes, the folder and its files stay.
  fs::create_directories(W("existing"));
  std::ofstream(W("existing/mine.txt")) << "mine";
  before_ = Snapshot(work_.path());
  ExpectRefused(
      "reconstruct --image_path images --output_path existing"
      " --ImageReader.camera_params 300,160,120,0",
      "existing/database.db");
}

TEST_F(BadInput, TerminatedRunRemovesItsStagedOutput) {
  // A scene large enough that writing its database takes a while; SIGTERM arrives while a staged
  // file exists (the script waits for one to appear).
  const std::string out = W("big");
  const test::CommandResult result = test::RunCommand(
      test::RamapCommand() + "synthesize --output_path " + Q(out) +
      " --Synthetic.num_images 300 --Synthetic.num_points 40000 --Synthetic.seed 1 2>&1 & pid=$!; "
      "for i in $(seq 1 4000); do "
      "  if ls -a " +
      Q(out) +
      " 2>/dev/null | grep -q ramap-tmp; then "
      "    kill -TERM $pid; echo signalled; break; fi; sleep 0.005; done; "
      "wait $pid; echo \"exit $?\"");
  ASSERT_NE(result.output.find("signalled"), std::string::npos)
      << "no staged output was seen to signal:\n"
      << result.output;
  EXPECT_NE(result.output.find("exit 143"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("unfinished outputs removed"), std::string::npos) << result.output;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(work_.path())) {
    EXPECT_EQ(entry.path().string().find("ramap-tmp"), std::string::npos) << entry.path();
  }
  EXPECT_FALSE(fs::exists(out)) << "the folder the run created is removed too";
}

}  // namespace
}  // namespace ramap
