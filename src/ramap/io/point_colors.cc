#include "ramap/io/point_colors.h"

#include <cmath>
#include <map>

#include "ramap/util/image_codecs.h"

namespace ramap {

PointColorSummary ColorPointsFromImages(const std::string& image_path,
                                        Reconstruction* reconstruction) {
  PointColorSummary summary;
  std::map<uint64_t, Eigen::Vector3d> sums;
  std::map<uint64_t, int> counts;
  for (const auto& [image_id, image] : reconstruction->images) {
    const cv::Mat bgr = ReadImageFile(image_path + "/" + image.name, cv::IMREAD_COLOR);
    if (bgr.empty()) {
      summary.unreadable_images.push_back(image.name);
      continue;
    }
    ++summary.num_images_read;
    for (const Point2D& point : image.points2D) {
      if (point.point3D_id == kInvalidPoint3DId) continue;
      const int col = static_cast<int>(std::floor(point.xy.x()));
      const int row = static_cast<int>(std::floor(point.xy.y()));
      if (col < 0 || row < 0 || col >= bgr.cols || row >= bgr.rows) continue;
      const cv::Vec3b pixel = bgr.at<cv::Vec3b>(row, col);
      auto [sum, inserted] = sums.emplace(point.point3D_id, Eigen::Vector3d::Zero());
      sum->second += Eigen::Vector3d(pixel[2], pixel[1], pixel[0]);
      ++counts[point.point3D_id];
    }
  }
  for (const auto& [point3D_id, sum] : sums) {
    auto it = reconstruction->points3D.find(point3D_id);
    if (it == reconstruction->points3D.end()) continue;
    const Eigen::Vector3d mean = (sum / counts.at(point3D_id)).array().round();
    it->second.color = mean.cast<uint8_t>();
  }
  return summary;
}

PointColorSummary ColorModelsFromImages(const std::string& image_path,
                                        std::vector<Reconstruction>* models) {
  PointColorSummary total;
  for (Reconstruction& model : *models) {
    const PointColorSummary colors = ColorPointsFromImages(image_path, &model);
    total.num_images_read += colors.num_images_read;
    total.unreadable_images.insert(total.unreadable_images.end(), colors.unreadable_images.begin(),
                                   colors.unreadable_images.end());
  }
  return total;
}

}  // namespace ramap
