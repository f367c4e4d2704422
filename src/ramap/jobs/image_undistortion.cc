#include "ramap/jobs/image_undistortion.h"

#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <opencv2/imgproc.hpp>
#include <set>

#include "ramap/geometry/camera_projection.h"
#include "ramap/util/error.h"
#include "ramap/util/image_codecs.h"
#include "ramap/util/parallel.h"
#include "ramap/util/staged_output.h"
#include "ramap/util/timer.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

// Removes the observations in `detached` (image id, point2D index) from their 3D points, then the
// points left with fewer than two observations.
void DetachObservations(const std::set<std::pair<uint32_t, uint32_t>>& detached,
                        Reconstruction* model) {
  for (auto it = model->points3D.begin(); it != model->points3D.end();) {
    std::vector<TrackElement>& track = it->second.track;
    track.erase(std::remove_if(track.begin(), track.end(),
                               [&](const TrackElement& e) {
                                 return detached.count({e.image_id, e.point2D_idx}) != 0;
                               }),
                track.end());
    if (track.size() >= 2) {
      ++it;
      continue;
    }
    for (const TrackElement& e : track) {
      model->images.at(e.image_id).points2D.at(e.point2D_idx).point3D_id = kInvalidPoint3DId;
    }
    it = model->points3D.erase(it);
  }
}

// For each pixel of `undistorted`, where to sample `distorted` (OpenCV's pixel indices).
void RemapTables(const Camera& distorted, const Camera& undistorted, cv::Mat* map_x,
                 cv::Mat* map_y) {
  const int width = static_cast<int>(undistorted.width);
  const int height = static_cast<int>(undistorted.height);
  map_x->create(height, width, CV_32FC1);
  map_y->create(height, width, CV_32FC1);
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      // COLMAP's pixel centres are at +0.5, OpenCV's at integers.
      const Eigen::Vector2d source =
          UndistortPixel(undistorted, distorted, Eigen::Vector2d(col + 0.5, row + 0.5));
      const bool valid = source.allFinite();
      map_x->at<float>(row, col) = valid ? static_cast<float>(source.x() - 0.5) : -1e6f;
      map_y->at<float>(row, col) = valid ? static_cast<float>(source.y() - 0.5) : -1e6f;
    }
  }
}

struct CameraRemap {
  cv::Mat map_x, map_y;
};

// Undistorts one image into a staged file beside its final path.
std::unique_ptr<StagedPath> UndistortImageFile(const std::string& source_path,
                                               const std::string& final_path, const Camera& camera,
                                               const CameraRemap& remap) {
  const cv::Mat image = ReadImageFile(source_path, cv::IMREAD_UNCHANGED);
  if (image.empty()) throw InputError(source_path, "cannot read the image");
  if (image.cols != static_cast<int>(camera.width) ||
      image.rows != static_cast<int>(camera.height)) {
    throw InputError(source_path,
                     "is " + std::to_string(image.cols) + " x " + std::to_string(image.rows) +
                         " pixels, its camera " + std::to_string(camera.camera_id) + " " +
                         std::to_string(camera.width) + " x " + std::to_string(camera.height));
  }
  cv::Mat undistorted;
  cv::remap(image, undistorted, remap.map_x, remap.map_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  std::vector<uint8_t> bytes;
  const std::string extension = fs::path(final_path).extension().string();
  if (!EncodeImage(extension.empty() ? ".png" : extension, undistorted, &bytes)) {
    throw InputError(final_path, "cannot encode the undistorted image");
  }
  std::error_code ec;
  fs::create_directories(fs::path(final_path).parent_path(), ec);
  if (ec) throw InputError(final_path, "cannot create its folder: " + ec.message());
  auto staged = std::make_unique<StagedPath>(final_path);
  std::ofstream file(staged->path(), std::ios::binary);
  file.write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  file.flush();
  if (!file) throw InputError(final_path, "write failed (disk full?)");
  return staged;
}

}  // namespace

Reconstruction UndistortReconstruction(const Reconstruction& model,
                                       const UndistortionOptions& options,
                                       const std::string& source) {
  Reconstruction undistorted = model;
  for (auto& [camera_id, camera] : undistorted.cameras) {
    camera = UndistortedCamera(model.cameras.at(camera_id), options, source);
  }
  std::set<std::pair<uint32_t, uint32_t>> detached;
  for (auto& [image_id, image] : undistorted.images) {
    const Camera& distorted = model.cameras.at(image.camera_id);
    const Camera& pinhole = undistorted.cameras.at(image.camera_id);
    for (size_t idx = 0; idx < image.points2D.size(); ++idx) {
      Point2D& point = image.points2D[idx];
      const Eigen::Vector2d moved = UndistortPixel(distorted, pinhole, point.xy);
      if (moved.allFinite()) {
        point.xy = moved;
      } else if (point.point3D_id != kInvalidPoint3DId) {
        detached.insert({image_id, static_cast<uint32_t>(idx)});
        point.point3D_id = kInvalidPoint3DId;
      }
    }
  }
  // Unobserved keypoints keep their old coordinates where they have no undistorted pixel.
  DetachObservations(detached, &undistorted);
  return undistorted;
}

ImageUndistortionSummary UndistortImages(const Reconstruction& model, const std::string& image_path,
                                         const std::string& output_path,
                                         const UndistortionOptions& options, ModelFormat format,
                                         int num_threads, std::ostream* progress) {
  Timer timer;
  options.Check();
  const fs::path images_out = fs::path(output_path) / "images";
  std::error_code ec;
  if (fs::exists(images_out, ec) && fs::exists(image_path, ec) &&
      fs::equivalent(images_out, image_path, ec)) {
    throw InputError(images_out.string(),
                     "is --image_path itself; the undistorted images would "
                     "replace the originals: choose another --output_path");
  }
  for (const auto& [image_id, image] : model.images) {
    const fs::path source = fs::path(image_path) / image.name;
    if (!fs::is_regular_file(source, ec)) throw InputError(source.string(), "image not found");
  }
  const Reconstruction undistorted = UndistortReconstruction(model, options, image_path);
  std::map<uint32_t, CameraRemap> remaps;
  for (const auto& [camera_id, camera] : model.cameras) {
    RemapTables(camera, undistorted.cameras.at(camera_id), &remaps[camera_id].map_x,
                &remaps[camera_id].map_y);
  }
  std::vector<const Image*> images;
  for (const auto& [image_id, image] : model.images) images.push_back(&image);
  std::vector<std::unique_ptr<StagedPath>> staged(images.size());
  ParallelFor(
      images.size(), num_threads,
      [&](size_t k) {
        const Image& image = *images[k];
        staged[k] = UndistortImageFile(
            (fs::path(image_path) / image.name).string(), (images_out / image.name).string(),
            model.cameras.at(image.camera_id), remaps.at(image.camera_id));
      },
      progress, "undistorting", "images");
  // Everything is written before anything appears under its final name.
  WriteColmapModel(undistorted, (fs::path(output_path) / "sparse").string(), format);
  for (const std::unique_ptr<StagedPath>& file : staged) file->Commit();
  ImageUndistortionSummary summary;
  summary.num_images = static_cast<int>(images.size());
  summary.seconds = timer.ElapsedSeconds();
  return summary;
}

}  // namespace ramap
