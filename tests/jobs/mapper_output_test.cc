// Writing the mapper's models over an earlier run's: every model stays whole throughout.
#include "ramap/jobs/mapper_output.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <thread>

#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

// A watcher looks at the earlier run's model many thousand times while a new run replaces it:
// before the models were exchanged atomically, the old one was removed first and the folder was
// missing for a moment (an interrupt there left neither model).
TEST(MapperOutput, ReplacingAModelNeverLeavesItMissing) {
  SyntheticSceneOptions options;
  options.num_images = 12;
  options.num_points = 300;
  MapperResult result;
  result.reconstructions.push_back(BuildSyntheticScene(options).ground_truth);
  test::TempDir dir;
  const fs::path output = fs::path(dir.path()) / "sparse";
  WriteMapperOutput(result, output.string(), ModelFormat::kBinary, {});
  std::atomic<bool> writing{true};
  std::atomic<int> looks{0}, missing{0};
  std::thread watcher([&]() {
    while (writing) {
      std::error_code ec;
      if (!fs::exists(output / "0" / "images.bin", ec)) ++missing;
      ++looks;
    }
  });
  for (int run = 0; run < 30; ++run) {
    WriteMapperOutput(result, output.string(), ModelFormat::kBinary, {{"run", run}});
  }
  writing = false;
  watcher.join();
  EXPECT_GT(looks.load(), 1000);
  EXPECT_EQ(missing.load(), 0) << "of " << looks.load() << " looks";
  // Only the models, the summary and the report are left: no staged or exchanged folder.
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(output)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"0", "report.html", "summary.json"}));
}

}  // namespace
}  // namespace ramap
