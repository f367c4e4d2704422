#include "ramap/io/pose_prior_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {

TEST(PosePriorFile, ReadsWhatItWroteWithAndWithoutDeviations) {
  test::TempDir dir;
  std::vector<PriorRecord> records(2);
  records[0] = {"a.jpg", Eigen::Vector3d(49.0112345678, 8.41651234567, 115.25), std::nullopt, ""};
  records[1] = {"b.jpg", Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0.5, 0.5, 2.0), ""};
  WritePriorFile(records, dir / "priors.txt");
  const std::vector<PriorRecord> read = ReadPriorFile(dir / "priors.txt");
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[0].image_name, "a.jpg");
  EXPECT_LT((read[0].value - records[0].value).norm(), 1e-9);
  EXPECT_FALSE(read[0].std_dev_m.has_value());
  EXPECT_EQ(read[1].std_dev_m.value(), Eigen::Vector3d(0.5, 0.5, 2.0));
  EXPECT_EQ(read[1].where, (dir / "priors.txt") + ":3");  // after the header comment
}

TEST(PosePriorFile, MalformedLinesNameFileAndLineButNaNIsAValue) {
  test::TempDir dir;
  std::ofstream(dir / "nan.txt") << "# comment\n\na.jpg nan 8.4 115\n";
  const std::vector<PriorRecord> read = ReadPriorFile(dir / "nan.txt");
  ASSERT_EQ(read.size(), 1u);
  EXPECT_TRUE(std::isnan(read[0].value.x()));

  std::ofstream(dir / "fields.txt") << "a.jpg 1 2 3\nb.jpg 1 2\n";
  test::ExpectInputError([&] { ReadPriorFile(dir / "fields.txt"); }, {"fields.txt:2"});
  std::ofstream(dir / "text.txt") << "a.jpg 1 north 3\n";
  EXPECT_THROW(ReadPriorFile(dir / "text.txt"), InputError);
  EXPECT_THROW(ReadPriorFile(dir / "missing.txt"), InputError);
  EXPECT_EQ(PriorCoordinatesFromName("ecef", "x"), PriorCoordinates::kEcef);
  EXPECT_THROW(PriorCoordinatesFromName("utm", "--PosePrior.type"), InputError);
}

}  // namespace
}  // namespace ramap
