// ExtractImageFeatures and ListImages: images listed by folder or by list, numbered in the order
// given, their cameras from the given intrinsics, the EXIF focal length or COLMAP's guess, shared
// only when asked, EXIF GPS as the prior position, and nothing readable named as an error.
#include "ramap/features/image_reader.h"

#include <gtest/gtest.h>

#include <exiv2/exiv2.hpp>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "exif_writer.h"
#include "ramap/util/error.h"
#include "test_support.h"
#include "texture_image.h"

namespace ramap {
namespace {

FeatureExtractionOptions FewFeatures() {
  FeatureExtractionOptions options;
  options.max_num_features = 200;
  return options;
}

TEST(ImageReader, ListedImagesAreNumberedInTheListsOrder) {
  test::TempDir dir;
  cv::imwrite(dir / "b.png", test::BlurredNoise(160, 120, 1));
  cv::imwrite(dir / "a.png", test::BlurredNoise(160, 120, 2));
  cv::imwrite(dir / "c.png", test::BlurredNoise(160, 120, 3));
  std::ofstream(dir / "list.txt") << "# two of the three, in this order\nc.png\n  a.png \n";
  const std::vector<std::string> names = ListImages(dir.path(), dir / "list.txt");
  EXPECT_EQ(names, (std::vector<std::string>{"c.png", "a.png"}));
  ExtractionSummary summary;
  const FeatureDatabase database =
      ExtractImageFeatures(dir.path(), names, ImageReaderOptions(), FewFeatures(), &summary);
  ASSERT_EQ(database.images.size(), 2u);
  EXPECT_EQ(database.images.at(1).name, "c.png");
  EXPECT_EQ(database.images.at(2).name, "a.png");
  EXPECT_EQ(summary.num_images, 2);
  int num_keypoints = 0;
  for (const auto& [id, keypoints] : database.keypoints) {
    EXPECT_EQ(database.descriptors.at(id).size(), keypoints.size());
    num_keypoints += static_cast<int>(keypoints.size());
  }
  EXPECT_EQ(summary.num_keypoints, num_keypoints);
  EXPECT_GT(num_keypoints, 50);
}

TEST(ImageReader, AFolderIsListedSortedWithItsImageFilesOnly) {
  test::TempDir dir;
  cv::imwrite(dir / "z.PNG", test::BlurredNoise(40, 30, 1));  // extensions in any case
  cv::imwrite(dir / "m.jpg", test::BlurredNoise(40, 30, 2));
  std::ofstream(dir / "notes.txt") << "not an image";
  EXPECT_EQ(ListImages(dir.path(), ""), (std::vector<std::string>{"m.jpg", "z.PNG"}));
  test::TempDir empty;
  std::ofstream(empty / "readme.md") << "no images here";
  test::ExpectInputError([&] { ListImages(empty.path(), ""); },
                         {empty.path(), "holds no image file"});
  test::ExpectInputError([&] { ListImages(empty / "missing", ""); }, {"not a folder of images"});
}

TEST(ImageReader, GivenIntrinsicsForEveryImageSharedOnlyWhenAsked) {
  test::TempDir dir;
  const std::vector<std::string> names = {"1.png", "2.png", "3.png"};
  for (size_t k = 0; k < names.size(); ++k) {
    cv::imwrite(dir / names[k], test::BlurredNoise(160, 120, static_cast<int>(k) + 4));
  }
  ImageReaderOptions reader;
  reader.camera_model = "PINHOLE";
  reader.camera_params = "150, 151, 80, 60";
  ExtractionSummary summary;
  const FeatureDatabase separate =
      ExtractImageFeatures(dir.path(), names, reader, FewFeatures(), &summary);
  ASSERT_EQ(separate.cameras.size(), 3u);
  for (const auto& [id, image] : separate.images) EXPECT_EQ(image.camera_id, id);
  for (const auto& [id, camera] : separate.cameras) {
    EXPECT_EQ(camera.model, CameraModel::kPinhole);
    EXPECT_EQ(camera.params, (std::vector<double>{150, 151, 80, 60}));
    EXPECT_TRUE(camera.has_prior_focal_length);
    EXPECT_EQ(camera.width, 160u);
    EXPECT_EQ(camera.height, 120u);
  }
  reader.single_camera = true;
  const FeatureDatabase shared =
      ExtractImageFeatures(dir.path(), names, reader, FewFeatures(), &summary);
  ASSERT_EQ(shared.cameras.size(), 1u);
  for (const auto& [id, image] : shared.images) EXPECT_EQ(image.camera_id, 1u);
}

TEST(ImageReader, ExifFocalLengthAndGpsAreUsed) {
  test::TempDir dir;
  cv::Mat colour;
  cv::cvtColor(test::BlurredNoise(200, 150, 7), colour, cv::COLOR_GRAY2BGR);
  test::WriteJpegWithGps(dir / "gps.jpg", colour, 48.137154, -11.575382, 519.5);
  {
    // 36 mm in 35 mm film terms: the focal length is the image's longest side (a 36 mm wide
    // frame), 200 px.
    auto image = Exiv2::ImageFactory::open(dir / "gps.jpg");
    image->readMetadata();
    Exiv2::ExifData exif = image->exifData();
    exif["Exif.Photo.FocalLengthIn35mmFilm"] = static_cast<uint16_t>(36);
    image->setExifData(exif);
    image->writeMetadata();
  }
  cv::imwrite(dir / "plain.png", test::BlurredNoise(200, 150, 8));
  ExtractionSummary summary;
  const FeatureDatabase database = ExtractImageFeatures(
      dir.path(), {"gps.jpg", "plain.png"}, ImageReaderOptions(), FewFeatures(), &summary);
  EXPECT_EQ(summary.num_images_with_gps, 1);
  const Image& tagged = database.images.at(1);
  ASSERT_TRUE(tagged.prior_translation.has_value());
  // Degrees, minutes and seconds to 1e-4 s: 3e-8 degrees.
  EXPECT_NEAR(tagged.prior_translation->x(), 48.137154, 1e-7);
  EXPECT_NEAR(tagged.prior_translation->y(), -11.575382, 1e-7);
  EXPECT_NEAR(tagged.prior_translation->z(), 519.5, 1e-6);
  EXPECT_EQ(tagged.prior_coordinate_system, PriorCoordinateSystem::kWgs84);
  const Camera& from_exif = database.cameras.at(tagged.camera_id);
  EXPECT_TRUE(from_exif.has_prior_focal_length);
  EXPECT_NEAR(from_exif.params[0], 200.0, 1e-9);
  // Without EXIF: COLMAP's guess, 1.2 times the longest side, not known.
  const Image& plain = database.images.at(2);
  EXPECT_FALSE(plain.prior_translation.has_value());
  const Camera& guessed = database.cameras.at(plain.camera_id);
  EXPECT_FALSE(guessed.has_prior_focal_length);
  EXPECT_EQ(guessed.params, (std::vector<double>{240, 100, 75, 0}));
}

TEST(ImageReader, BadIntrinsicsAndNothingReadableAreErrors) {
  test::TempDir dir;
  cv::imwrite(dir / "a.png", test::BlurredNoise(160, 120, 1));
  ImageReaderOptions reader;
  reader.camera_model = "SIMPLE_RADIAL";
  reader.camera_params = "150,80,60";
  ExtractionSummary summary;
  test::ExpectInputError(
      [&] { ExtractImageFeatures(dir.path(), {"a.png"}, reader, FewFeatures(), &summary); },
      {"--ImageReader.camera_params", "SIMPLE_RADIAL takes 4 parameters, 3 given"});
  std::ofstream(dir / "broken.png") << "not an image";
  test::ExpectInputError(
      [&] {
        ExtractImageFeatures(dir.path(), {"broken.png", "gone.png"}, ImageReaderOptions(),
                             FewFeatures(), &summary);
      },
      {dir.path(), "none of the 2 images could be read", "broken.png"});
}

}  // namespace
}  // namespace ramap
