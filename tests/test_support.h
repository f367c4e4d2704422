// Helpers shared by the tests: where the real data lives, temporary folders, running the ramap
// and colmap binaries.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ramap/eval/pose_metrics.h"
#include "ramap/mapper/mapper.h"
#include "ramap/scene/camera.h"
#include "ramap/synthetic/synthetic_scene.h"

namespace ramap::test {

// ../shared/data beside the checkout, or $RAMAP_DATA_DIR when set.
std::string SharedDataDir();
// SharedDataDir()/relative when it exists, else "".
std::string SharedDataPath(const std::string& relative);

// Whether the `colmap` binary is on the PATH.
bool ColmapAvailable();

// COLMAP 4.1.1 built by scripts/peers.sh ($RAMAP_COLMAP4, else build-peers/ in the checkout), or ""
// when there is none: tests that run it skip visibly without it.
std::string Colmap4Binary();

// The built `ramap` binary.
std::string RamapBinary();
// The start of a shell command line that runs it: the quoted binary and a space.
std::string RamapCommand();

// A file's whole contents, byte for byte ("" when it cannot be read), and a JSON file parsed.
std::string ReadFileBytes(const std::string& path);
nlohmann::json ReadJsonFile(const std::string& path);

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};
// Runs a shell command line, capturing its output.
CommandResult RunCommand(const std::string& command_line);

// COLMAP run on a subset of real images, cached on disk under the build folder (keyed by every
// argument) so that tests share one extraction and one mapper run. Each call that finds no cached
// result runs COLMAP on the CPU; tests keep subsets small and max_image_size low.
struct ColmapRun {
  std::string image_dir;                 // folder of the images
  std::vector<std::string> image_names;  // the subset, by file name (empty: every image)
  std::string camera_model = "PINHOLE";  // one shared camera with known intrinsics
  std::string camera_params;             // "fx,fy,cx,cy" at FULL resolution (scaled by COLMAP)
  int max_image_size = 640;
  bool sequential_matching = false;  // exhaustive by default
};
// Four Herz-Jesus-P8 images (0000-0003 of `image_dir`) with their calibration, at 640 px: the
// subset every test of real images shares, so that COLMAP runs once for all of them.
ColmapRun HerzJesusFourImages(const std::string& image_dir);

// Path of a database built by colmap feature_extractor + matcher; "" and a gtest failure if COLMAP
// fails.
std::string CachedColmapDatabase(const ColmapRun& run);
// Path of the sparse model folder (sparse/0) of `colmap mapper` on that database, intrinsics fixed.
std::string CachedColmapModel(const ColmapRun& run);

// The mapper's options without bundle adjustment, for tests of the averaging stages (the
// default refines).
MapperOptions AveragingOnly();

// Camera 1: a 640 x 480 PINHOLE camera with focal lengths fx, fy and the principal point at the
// image centre.
Camera VgaPinholeCamera(double fx = 500, double fy = 500);

// 16 views all around an object from varied distances (so that the optical axes do not meet in
// one point at equal distances, where F leaves the focal length free), 3000 points, 0.5 px of
// noise and 10% wrong matches.
SyntheticSceneOptions NoisyCollection(uint64_t seed);

// A scene without keypoint noise or wrong matches: 1500 points, seed 11.
SyntheticSceneOptions NoiseFree(SyntheticLayout layout, SyntheticPath path, int num_images);

// `options` with `num_pairs` pairs aliased as a facade's repeat gives them: at most 8 frames
// apart, the true rotation with the second camera moved by `shift_m`, matches starting from the
// first image's observations (so that they join its points' tracks).
SyntheticSceneOptions WithFacadeRepeats(SyntheticSceneOptions options, int num_pairs,
                                        double shift_m);

// A car waiting at a light: a noise-free 30-frame line (images 1-30) in which images 10-12 share
// one centre and turn a little, and image 11's only verified pairs are its pure rotations to 10
// and 12, so that it has no direction to any camera.
SyntheticScene StandstillLineScene();

// `model`'s poses scored against `scene`'s truth, every image of the truth an input (unregistered
// ones count as failures).
PoseEvaluation EvaluateAgainstTruth(const Reconstruction& model, const SyntheticScene& scene);

// The data a report.html was drawn from (its <script id="ramap-data">); a test failure and null
// when the page has none.
nlohmann::json ReportPageData(const std::string& report_path);

// Runs `action` and expects an InputError whose message contains every one of `parts`.
void ExpectInputError(const std::function<void()>& action, const std::vector<std::string>& parts);

// A fresh folder under the system's temporary folder, removed with its contents at scope end.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  std::string operator/(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

}  // namespace ramap::test

// Skips the current test, visibly, when a shared data set is absent; defines `var` as its path.
#define RAMAP_REQUIRE_SHARED_DATA(var, relative)                               \
  const std::string var = ::ramap::test::SharedDataPath(relative);             \
  if (var.empty()) {                                                           \
    GTEST_SKIP() << "shared data '" << relative << "' not found under "        \
                 << ::ramap::test::SharedDataDir() << " (set RAMAP_DATA_DIR)"; \
  }

// Skips the current test, visibly, when the colmap binary is not installed.
#define RAMAP_REQUIRE_COLMAP()                                                       \
  if (!::ramap::test::ColmapAvailable()) {                                           \
    GTEST_SKIP() << "colmap binary not found (scripts/install-deps.sh installs it)"; \
  }
