// The image codecs' plug-in: images encoded and read back through it, and the empty answers for
// files and formats it cannot handle.
#include "ramap/util/image_codecs.h"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/core.hpp>

#include "test_support.h"

namespace ramap {
namespace {

// A small colour image whose every pixel differs from its neighbours.
cv::Mat Gradient() {
  cv::Mat image(24, 32, CV_8UC3);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      image.at<cv::Vec3b>(y, x) = cv::Vec3b(x * 8, y * 10, (x + y) * 4);
    }
  }
  return image;
}

void WriteBytes(const std::vector<uchar>& bytes, const std::string& path) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

TEST(ImageCodecs, PngRoundTripIsLossless) {
  test::TempDir dir;
  const cv::Mat image = Gradient();
  std::vector<uchar> bytes;
  ASSERT_TRUE(EncodeImage(".png", image, &bytes));
  ASSERT_FALSE(bytes.empty());
  WriteBytes(bytes, dir / "gradient.png");
  const cv::Mat read = ReadImageFile(dir / "gradient.png", cv::IMREAD_COLOR);
  ASSERT_EQ(read.type(), CV_8UC3);
  ASSERT_EQ(read.size(), image.size());
  EXPECT_EQ(cv::norm(read, image, cv::NORM_INF), 0.0);
}

TEST(ImageCodecs, GreyscaleFlagGivesOneChannel) {
  test::TempDir dir;
  std::vector<uchar> bytes;
  ASSERT_TRUE(EncodeImage(".png", Gradient(), &bytes));
  WriteBytes(bytes, dir / "gradient.png");
  const cv::Mat grey = ReadImageFile(dir / "gradient.png", cv::IMREAD_GRAYSCALE);
  EXPECT_EQ(grey.type(), CV_8UC1);
  EXPECT_EQ(grey.size(), cv::Size(32, 24));
}

TEST(ImageCodecs, JpegIsDecodedAtItsSize) {
  test::TempDir dir;
  std::vector<uchar> bytes;
  ASSERT_TRUE(EncodeImage(".jpg", Gradient(), &bytes));
  WriteBytes(bytes, dir / "gradient.jpg");
  const cv::Mat read = ReadImageFile(dir / "gradient.jpg", cv::IMREAD_COLOR);
  EXPECT_EQ(read.size(), cv::Size(32, 24));
  // JPEG is lossy: a smooth gradient comes back within a few grey levels.
  EXPECT_LT(cv::norm(read, Gradient(), cv::NORM_L1) / (32 * 24 * 3), 8.0);
}

TEST(ImageCodecs, MissingOrUndecodableFilesGiveAnEmptyImage) {
  test::TempDir dir;
  EXPECT_TRUE(ReadImageFile(dir / "absent.png", cv::IMREAD_COLOR).empty());
  std::ofstream(dir / "text.png") << "not an image";
  EXPECT_TRUE(ReadImageFile(dir / "text.png", cv::IMREAD_COLOR).empty());
}

TEST(ImageCodecs, UnknownFormatCannotBeEncoded) {
  std::vector<uchar> bytes;
  EXPECT_FALSE(EncodeImage(".not-a-format", Gradient(), &bytes));
}

}  // namespace
}  // namespace ramap
