#include "ramap/features/image_reader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>

#include "ramap/geometry/camera_projection.h"
#include "ramap/io/exif.h"
#include "ramap/io/image_list.h"
#include "ramap/util/error.h"
#include "ramap/util/image_codecs.h"
#include "ramap/util/number_list.h"
#include "ramap/util/option_check.h"
#include "ramap/util/parallel.h"
#include "ramap/util/timer.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

bool HasImageExtension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  static const std::vector<std::string> known = {".png", ".jpg", ".jpeg", ".pgm", ".ppm",
                                                 ".bmp", ".tif", ".tiff", ".webp"};
  return std::find(known.begin(), known.end(), extension) != known.end();
}

// The camera of an image of width x height under `options`: the given intrinsics, else the EXIF
// focal length, else COLMAP's guess. EXIF of a cropped image is a start, not a prior: its camera is
// marked unknown, as a guess is.
Camera MakeCamera(const ImageReaderOptions& options, int width, int height,
                  const std::optional<ExifFocalLength>& exif) {
  Camera camera;
  camera.model = *CameraModelFromName(options.camera_model);
  camera.width = static_cast<uint64_t>(width);
  camera.height = static_cast<uint64_t>(height);
  if (!options.camera_params.empty()) {
    camera.params = ParseNumberList(options.camera_params, "--ImageReader.camera_params");
    camera.has_prior_focal_length = true;
    return camera;
  }
  camera.has_prior_focal_length = exif.has_value() && !exif->cropped;
  const double focal =
      exif ? exif->focal_px : options.default_focal_length_factor * std::max(width, height);
  camera.params.assign(NumCameraParams(camera.model), 0.0);
  // f (or fx, fy) first, then the principal point, then distortion at zero.
  const bool one_focal =
      camera.model == CameraModel::kSimplePinhole || camera.model == CameraModel::kSimpleRadial ||
      camera.model == CameraModel::kRadial || camera.model == CameraModel::kSimpleRadialFisheye ||
      camera.model == CameraModel::kRadialFisheye;
  size_t k = 0;
  camera.params[k++] = focal;
  if (!one_focal) camera.params[k++] = focal;
  camera.params[k++] = 0.5 * width;
  camera.params[k++] = 0.5 * height;
  return camera;
}

}  // namespace

void ImageReaderOptions::Check() const {
  CheckOptionValues(ImageReaderOptionTable(), *this);
  if (camera_params.empty()) return;
  const CameraModel model = *CameraModelFromName(camera_model);
  const std::vector<double> params = ParseNumberList(camera_params, "--ImageReader.camera_params");
  if (static_cast<int>(params.size()) != NumCameraParams(model)) {
    throw InputError("--ImageReader.camera_params",
                     camera_model + " takes " + std::to_string(NumCameraParams(model)) +
                         " parameters, " + std::to_string(params.size()) + " given");
  }
}

std::vector<std::string> ListImages(const std::string& image_path,
                                    const std::string& image_list_path) {
  if (!image_list_path.empty()) return ReadImageList(image_list_path);
  std::vector<std::string> names;
  std::error_code error;
  if (!fs::is_directory(image_path, error)) {
    throw InputError(image_path, "not a folder of images");
  }
  for (const fs::directory_entry& entry : fs::directory_iterator(image_path, error)) {
    if (entry.is_regular_file() && HasImageExtension(entry.path())) {
      names.push_back(entry.path().filename().string());
    }
  }
  if (error) throw InputError(image_path, "cannot list the folder: " + error.message());
  if (names.empty()) throw InputError(image_path, "holds no image file (.png, .jpg, ...)");
  std::sort(names.begin(), names.end());
  return names;
}

namespace {

// One image read and its features extracted, or why not.
struct ImageResult {
  std::string problem;  // empty when read
  int width = 0, height = 0;
  std::optional<ExifFocalLength> exif_focal;
  std::optional<GeodeticPoint> exif_gps;
  ImageFeatures features;
};

ImageResult ReadImageFeatures(const std::string& path, const ImageReaderOptions& reader,
                              const FeatureExtractionOptions& extraction) {
  ImageResult result;
  std::error_code error;
  if (!fs::is_regular_file(path, error)) {
    result.problem = "no such file";
    return result;
  }
  if (fs::file_size(path, error) == 0) {
    result.problem = "empty file";
    return result;
  }
  const cv::Mat grey = ReadImageFile(path, cv::IMREAD_GRAYSCALE);
  if (grey.empty()) {
    result.problem = "not an image OpenCV can read";
    return result;
  }
  result.width = grey.cols;
  result.height = grey.rows;
  // Smaller than a feature's support region: no detector finds anything there, and OpenCV's
  // pyramids throw on it.
  constexpr int kMinImageSide = 16;
  if (grey.cols < kMinImageSide || grey.rows < kMinImageSide) {
    result.problem = "too small (" + std::to_string(grey.cols) + "x" + std::to_string(grey.rows) +
                     " pixels; at least " + std::to_string(kMinImageSide) + " on each side)";
    return result;
  }
  try {
    result.features = ExtractFeatures(grey, extraction);
  } catch (const cv::Exception& exception) {
    result.problem = std::string("OpenCV cannot extract features: ") + exception.what();
    return result;
  }
  if (reader.camera_params.empty()) {
    result.exif_focal = ReadExifFocalLength(path, grey.cols, grey.rows);
  }
  result.exif_gps = ExifGpsPosition(path);
  return result;
}

// Where the focal length of the camera made for `result` came from, for the user.
std::string FocalSource(const ImageReaderOptions& reader, const ImageResult& result) {
  if (!reader.camera_params.empty()) return "--ImageReader.camera_params";
  if (!result.exif_focal) {
    return "guess: " + FormatOptionNumber(reader.default_focal_length_factor) +
           " x the longest side (no EXIF focal length)";
  }
  const ExifFocalLength& exif = *result.exif_focal;
  std::string source = "EXIF (" + exif.source + "): " + FormatOptionNumber(exif.focal_px) + " px";
  if (!exif.note.empty()) source += "; " + exif.note;
  return source;
}

}  // namespace

FeatureDatabase ExtractImageFeatures(const std::string& image_path,
                                     const std::vector<std::string>& names,
                                     const ImageReaderOptions& reader,
                                     const FeatureExtractionOptions& extraction,
                                     ExtractionSummary* summary, std::ostream* progress) {
  reader.Check();
  extraction.Check();
  Timer timer;
  std::vector<ImageResult> results(names.size());
  ParallelFor(
      names.size(), reader.num_threads,
      [&](size_t k) {
        results[k] = ReadImageFeatures(image_path + "/" + names[k], reader, extraction);
      },
      progress, "feature extraction", "images");

  FeatureDatabase database;
  std::map<std::pair<int, int>, uint32_t> shared_cameras;  // single_camera: one per image size
  uint32_t next_image_id = 1;
  *summary = ExtractionSummary();
  for (size_t k = 0; k < names.size(); ++k) {
    ImageResult& result = results[k];
    if (!result.problem.empty()) {
      summary->skipped_images.push_back(names[k] + ": " + result.problem);
      continue;
    }
    uint32_t camera_id = 0;
    const std::pair<int, int> size(result.width, result.height);
    if (reader.single_camera && shared_cameras.count(size)) {
      camera_id = shared_cameras.at(size);
    } else {
      Camera camera = MakeCamera(reader, result.width, result.height, result.exif_focal);
      camera.camera_id = static_cast<uint32_t>(database.cameras.size()) + 1;
      summary->focal_sources[camera.camera_id] = FocalSource(reader, result);
      CheckCameraParams(camera, "--ImageReader.camera_params");
      camera_id = camera.camera_id;
      database.cameras[camera_id] = camera;
      if (reader.single_camera) shared_cameras[size] = camera_id;
    }
    Image image;
    image.image_id = next_image_id++;
    image.name = names[k];
    image.camera_id = camera_id;
    // As COLMAP's ImageReader: GPS in the prior position columns as latitude, longitude, altitude.
    if (const auto& gps = result.exif_gps) {
      image.prior_translation =
          Eigen::Vector3d(gps->latitude_deg, gps->longitude_deg, gps->altitude_m);
      image.prior_coordinate_system = PriorCoordinateSystem::kWgs84;
      ++summary->num_images_with_gps;
    }
    database.images[image.image_id] = image;
    summary->num_keypoints += static_cast<int>(result.features.keypoints.size());
    database.keypoints[image.image_id] = std::move(result.features.keypoints);
    database.descriptors[image.image_id] = std::move(result.features.descriptors);
    ++summary->num_images;
  }
  summary->seconds = timer.ElapsedSeconds();
  if (database.images.empty()) {
    throw InputError(image_path,
                     "none of the " + std::to_string(names.size()) +
                         " images could be read (first: " + summary->skipped_images.front() + ")");
  }
  return database;
}

}  // namespace ramap
