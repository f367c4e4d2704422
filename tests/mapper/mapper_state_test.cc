// The mapper's state helpers: an edge named by its images, and a component's stage recorded into
// its own report and onto the pass's progress stream.
#include "ramap/mapper/mapper_state.h"

#include <gtest/gtest.h>

#include <sstream>

#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

TEST(MapperState, PairNameIsBothImageNamesInTheGivenOrder) {
  FeatureDatabase database;
  database.images[3].name = "left/0003.png";
  database.images[8].name = "right/0008.png";
  EXPECT_EQ(PairName(database, 3, 8), "left/0003.png right/0008.png");
  EXPECT_EQ(PairName(database, 8, 3), "right/0008.png left/0003.png");
}

TEST(MapperState, RecordStageWritesTheComponentsReportAndThePassProgress) {
  const FeatureDatabase database;
  const MapperOptions options;
  const std::map<uint32_t, Camera> cameras;
  const ImageBearings bearings;
  const std::vector<ImagePair> pairs;
  const std::vector<uint32_t> order;
  const PosePriors priors;
  std::ostringstream progress;
  PassInput input{database, options, cameras, bearings, pairs, order, false, priors};
  input.progress = &progress;

  ComponentState first, second;
  RecordStage(input, stage::kRotationAveraging, 1.25, "30 images", &first);
  RecordStage(input, stage::kRotationAveraging, 0.5, "12 images", &second);
  RecordStage(input, stage::kRotationAveraging, 0.25, "again", &first);
  // Each component keeps its own times.
  ASSERT_EQ(first.report.timings.size(), 1u);
  EXPECT_EQ(first.report.timings[0].seconds, 1.5);
  ASSERT_EQ(second.report.timings.size(), 1u);
  EXPECT_EQ(second.report.timings[0].seconds, 0.5);
  // The lines go to the pass's progress stream, in the stage log's format.
  std::ostringstream expected;
  PrintStageLine(expected, stage::kRotationAveraging, 1.25, "30 images");
  PrintStageLine(expected, stage::kRotationAveraging, 0.5, "12 images");
  PrintStageLine(expected, stage::kRotationAveraging, 0.25, "again");
  EXPECT_EQ(progress.str(), expected.str());

  // Without a progress stream, nothing is printed but the time is still recorded.
  input.progress = nullptr;
  RecordStage(input, stage::kTriangulation, 2.0, "quiet", &second);
  EXPECT_EQ(second.report.timings.size(), 2u);
  EXPECT_EQ(progress.str(), expected.str());
}

}  // namespace
}  // namespace ramap
