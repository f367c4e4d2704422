// Images of a folder or a list, read as grey images with the cameras they were taken with, and
// their features: the first half of the image-list input (the database that COLMAP's
// feature_extractor would write, made with OpenCV's ORB or SIFT).
#pragma once

#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "ramap/features/feature_extraction.h"
#include "ramap/scene/features.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct ImageReaderOptions {
  // COLMAP's ImageReader options. Without camera_params the focal length comes from the image's
  // EXIF tags (io/exif.h), else it is default_focal_length_factor times the longest side (COLMAP's
  // guess, 1.2); the principal point is the image centre, other parameters zero. With them, one
  // "a,b,c,..." list in the model's order at full resolution, used for every image.
  std::string camera_model = "SIMPLE_RADIAL";
  std::string camera_params;
  // One camera for every image (of one size; an image of another size gets its own camera).
  bool single_camera = false;
  double default_focal_length_factor = 1.2;
  int num_threads = 2;

  void Check() const;  // throws InputError naming the option
};

// Its options (--FeatureExtraction.*, --ImageReader.*), each declared once with its range and help
// (util/option_table.h): the command line, Check(), summary.json and Python read them.
const OptionTable<ImageReaderOptions>& ImageReaderOptionTable();

// Image file names in `image_path` (its files with an image extension, sorted), or the names in
// `image_list_path` (one per line, relative to image_path) when that is given. Throws InputError
// when the folder or list cannot be read or names no image.
std::vector<std::string> ListImages(const std::string& image_path,
                                    const std::string& image_list_path);

struct ExtractionSummary {
  int num_images = 0;                       // read and with features
  std::vector<std::string> skipped_images;  // "NAME: reason" for each image that was not
  int num_keypoints = 0;
  int num_images_with_gps = 0;  // EXIF GPS stored as the image's prior position
  // Each camera's focal length: the user's, EXIF's (with its resize or crop), or the guess.
  std::map<uint32_t, std::string> focal_sources;
  double seconds = 0.0;
};

// Reads every image of `names` under image_path (colour or grey, any size OpenCV reads), makes
// its camera and extracts its features: a database with cameras, images, keypoints and
// descriptors (ids from 1 in name order). Unreadable and empty files are skipped and listed in the
// summary, never fatal. With `progress`, one line counts the images done in tens of percent.
FeatureDatabase ExtractImageFeatures(const std::string& image_path,
                                     const std::vector<std::string>& names,
                                     const ImageReaderOptions& reader,
                                     const FeatureExtractionOptions& extraction,
                                     ExtractionSummary* summary, std::ostream* progress = nullptr);

}  // namespace ramap
