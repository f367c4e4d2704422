// RunMapperJob: a database file in, the models, summary.json and report out (or nothing when no
// output is asked for), the database's priors used as the options say, and a run that can make no
// model leaving nothing behind.
#include "ramap/jobs/mapper_job.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

SyntheticSceneOptions SmallLine() {
  SyntheticSceneOptions options =
      test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kLine, 15);
  options.num_points = 800;
  return options;
}

// A job on a noise-free 15-frame line written to `dir`/database.db, averaging only (fast).
MapperJob Job(const test::TempDir& dir, const SyntheticScene& scene) {
  WriteColmapDatabase(scene.database, dir / "database.db");
  MapperJob job;
  job.database_path = dir / "database.db";
  job.output_path = dir / "sparse";
  job.options = test::AveragingOnly();
  return job;
}

TEST(MapperJob, WritesTheModelsSummaryAndReport) {
  test::TempDir dir;
  const SyntheticScene scene = BuildSyntheticScene(SmallLine());
  const MapperJob job = Job(dir, scene);
  std::ostringstream progress, warnings;
  const MapperResult result = RunMapperJob(job, &progress, &warnings);
  ASSERT_EQ(result.reconstructions.size(), 1u);

  const Reconstruction written = ReadColmapModel(dir / "sparse/0");
  EXPECT_EQ(written.images.size(), 15u);
  EXPECT_EQ(written.points3D.size(), result.reconstructions[0].points3D.size());
  // What was written is what the job returned (binary float64: bit for bit).
  for (const auto& [id, image] : result.reconstructions[0].images) {
    EXPECT_EQ(written.images.at(id).name, image.name);
    EXPECT_EQ(written.images.at(id).cam_from_world.translation, image.cam_from_world.translation);
  }

  const nlohmann::json summary = test::ReadJsonFile(dir / "sparse/summary.json");
  EXPECT_EQ(summary["run"]["command"], "mapper");
  EXPECT_EQ(summary["run"]["database_path"], job.database_path);
  EXPECT_EQ(summary["run"]["database"]["generation"], "COLMAP 3.8-3.9");
  EXPECT_EQ(summary["run"]["options"]["Mapper"]["refine"], false);
  EXPECT_TRUE(fs::exists(dir / "sparse/report.html"));
  const std::string lines = progress.str();
  EXPECT_NE(lines.find("reading the database"), std::string::npos) << lines;
  EXPECT_NE(lines.find("15 images"), std::string::npos) << lines;
  EXPECT_NE(lines.find("writing the models"), std::string::npos) << lines;
  EXPECT_EQ(warnings.str(), "");
}

TEST(MapperJob, WithoutAnOutputPathNothingIsWritten) {
  test::TempDir dir;
  MapperJob job = Job(dir, BuildSyntheticScene(SmallLine()));
  job.output_path.clear();
  const MapperResult result = RunMapperJob(job, nullptr, nullptr);
  EXPECT_EQ(result.reconstructions.size(), 1u);
  std::vector<std::string> entries;
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    entries.push_back(entry.path().filename().string());
  }
  EXPECT_EQ(entries, std::vector<std::string>{"database.db"});
}

TEST(MapperJob, TheDatabasesPriorsPlaceTheModelInTheirFrame) {
  test::TempDir dir;
  // An orbit: priors on a line would leave the turn about it free.
  SyntheticScene scene = BuildSyntheticScene(
      test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kCircle, 15));
  // Each image's true centre as a Cartesian prior, in a frame 1000 units away and 3 times larger.
  for (auto& [id, image] : scene.database.images) {
    const Eigen::Vector3d center = CameraCenter(scene.ground_truth.images.at(id).cam_from_world);
    image.prior_translation = 3.0 * center + Eigen::Vector3d(1000, 0, 0);
  }
  MapperJob job = Job(dir, scene);
  job.options.prior_source.type = "xyz";
  // Exact priors: a centimetre of standard deviation, so that the fit is certain.
  job.options.prior_source.std_x_m = job.options.prior_source.std_y_m =
      job.options.prior_source.std_z_m = 0.01;
  const MapperResult result = RunMapperJob(job, nullptr, nullptr);
  ASSERT_EQ(result.reconstructions.size(), 1u);
  EXPECT_TRUE(result.summary.components[0].prior_alignment.aligned)
      << result.summary.components[0].prior_alignment.problem;
  double max_miss = 0;
  for (const auto& [id, image] : result.reconstructions[0].images) {
    max_miss = std::max(max_miss, (CameraCenter(image.cam_from_world) -
                                   *scene.database.images.at(id).prior_translation)
                                      .norm());
  }
  // Exact priors of exact poses: the fit and the priors' rows agree up to the keypoints' float32
  // rounding, far below a millimetre on an orbit 60 units across.
  EXPECT_LT(max_miss, 1e-3);
}

TEST(MapperJob, UnreadableImagesGiveAWarningNotAFailure) {
  test::TempDir dir;
  MapperJob job = Job(dir, BuildSyntheticScene(SmallLine()));
  fs::create_directories(dir / "images");  // none of the database's images are in it
  job.image_path = dir / "images";
  job.command = "ramap test";
  std::ostringstream warnings;
  const MapperResult result = RunMapperJob(job, nullptr, &warnings);
  EXPECT_EQ(result.reconstructions.size(), 1u);
  EXPECT_NE(warnings.str().find("ramap test: warning: cannot read " + job.image_path +
                                "/frame_000001.png"),
            std::string::npos)
      << warnings.str();
}

TEST(MapperJob, NoModelToMakeLeavesNoOutput) {
  test::TempDir dir;
  MapperJob job = Job(dir, BuildSyntheticScene(SmallLine()));
  job.options.min_component_size = 20;  // more images than the database has
  EXPECT_THROW(RunMapperJob(job, nullptr, nullptr), NothingReconstructed);
  EXPECT_FALSE(fs::exists(dir / "sparse/0"));
  EXPECT_FALSE(fs::exists(dir / "sparse/summary.json"));
}

TEST(MapperJob, BadOptionsAndOutputsAreRefusedBeforeTheDatabaseIsRead) {
  test::TempDir dir;
  MapperJob job = Job(dir, BuildSyntheticScene(SmallLine()));
  job.database_path = dir / "no_such.db";  // never read: the checks come first
  MapperJob threads = job;
  threads.options.num_threads = 0;
  test::ExpectInputError([&] { RunMapperJob(threads, nullptr, nullptr); },
                         {"--Mapper.num_threads"});
  MapperJob onto_database = Job(dir, BuildSyntheticScene(SmallLine()));
  onto_database.output_path = onto_database.database_path;
  test::ExpectInputError([&] { RunMapperJob(onto_database, nullptr, nullptr); }, {"--output_path"});
}

}  // namespace
}  // namespace ramap
