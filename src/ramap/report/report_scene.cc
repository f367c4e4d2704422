#include "ramap/report/report_scene.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <unordered_map>
#include <vector>

#include "ramap/geometry/camera_projection.h"
#include "ramap/scene/image_order.h"

namespace ramap {
namespace {

// `value` rounded to `digits` significant digits: the page's numbers stay short (JSON writes the
// shortest text that reads back the rounded double). Not finite: null.
nlohmann::json Rounded(double value, int digits) {
  if (!std::isfinite(value)) return nullptr;
  char text[40];
  std::snprintf(text, sizeof(text), "%.*g", digits, value);
  return std::strtod(text, nullptr);
}

void AppendVector(const Eigen::Vector3d& v, int digits, nlohmann::json* out) {
  for (int k = 0; k < 3; ++k) out->push_back(Rounded(v[k], digits));
}

// The tangents of half the horizontal and vertical fields of view.
Eigen::Vector2d HalfFieldOfView(const Camera& camera) {
  const Eigen::Matrix3d k = CalibrationMatrix(camera);
  if (!(k(0, 0) > 0) || !(k(1, 1) > 0) || camera.width == 0 || camera.height == 0) {
    return {0.5, 0.375};
  }
  return {camera.width / (2.0 * k(0, 0)), camera.height / (2.0 * k(1, 1))};
}

// Mean reprojection error (pixels) of each image's observations of the model's points.
std::unordered_map<uint32_t, double> MeanReprojectionErrors(const Reconstruction& model) {
  std::unordered_map<uint32_t, std::pair<double, int>> sums;
  for (const auto& [point_id, point] : model.points3D) {
    for (const TrackElement& element : point.track) {
      const auto image = model.images.find(element.image_id);
      if (image == model.images.end() || element.point2D_idx >= image->second.points2D.size()) {
        continue;
      }
      const auto camera = model.cameras.find(image->second.camera_id);
      if (camera == model.cameras.end()) continue;
      const Eigen::Vector2d projected =
          ProjectToPixel(camera->second, image->second.cam_from_world * point.xyz);
      const double error = (projected - image->second.points2D[element.point2D_idx].xy).norm();
      if (!std::isfinite(error)) continue;
      auto& [sum, count] = sums[element.image_id];
      sum += error;
      ++count;
    }
  }
  std::unordered_map<uint32_t, double> means;
  for (const auto& [image_id, sum_count] : sums) {
    means[image_id] = sum_count.first / sum_count.second;
  }
  return means;
}

// The model's registered images in capture order.
std::vector<const Image*> ImagesInCaptureOrder(const Reconstruction& model) {
  std::vector<const Image*> images;
  std::vector<std::string> names;
  for (const auto& [image_id, image] : model.images) {
    images.push_back(&image);
    names.push_back(image.name);
  }
  std::vector<const Image*> ordered;
  for (const size_t k : CaptureOrder(names)) ordered.push_back(images[k]);
  return ordered;
}

nlohmann::json PointsJson(const Reconstruction& model, const Sim3d& transform,
                          const Eigen::Vector3d& origin, size_t max_points, int digits) {
  nlohmann::json xyz = nlohmann::json::array();
  nlohmann::json rgb = nlohmann::json::array();
  const size_t total = model.points3D.size();
  const double stride = total > max_points ? static_cast<double>(total) / max_points : 1.0;
  double next = 0.0;
  size_t index = 0;
  bool coloured = false;
  for (const auto& [point_id, point] : model.points3D) {
    if (max_points == 0) break;
    if (static_cast<double>(index++) < next) continue;
    next += stride;
    if (!point.xyz.allFinite()) continue;
    AppendVector(transform * point.xyz - origin, digits, &xyz);
    for (int k = 0; k < 3; ++k) rgb.push_back(point.color[k]);
    coloured = coloured || point.color != Eigen::Matrix<uint8_t, 3, 1>::Zero();
  }
  return {{"total", total},
          {"count", xyz.size() / 3},
          {"xyz", xyz},
          {"rgb", coloured ? rgb : nlohmann::json()}};
}

}  // namespace

Eigen::Vector3d SceneMiddle(const Reconstruction& model, const Sim3d& transform) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (const auto& [image_id, image] : model.images) {
    const Eigen::Vector3d center = transform * image.cam_from_world.Inverse().translation;
    if (!center.allFinite()) continue;
    sum += center;
    ++count;
  }
  return count > 0 ? Eigen::Vector3d(sum / count) : Eigen::Vector3d::Zero();
}

nlohmann::json ReportModelJson(const std::string& name, const Reconstruction& model,
                               const Sim3d& reference_from_model, const PoseEvaluation* evaluation,
                               size_t max_points, const ReportSceneOptions& options) {
  std::unordered_map<std::string, const ImageEvaluation*> errors;
  if (evaluation != nullptr) {
    for (const ImageEvaluation& image : evaluation->images) errors[image.name] = &image;
  }
  const std::unordered_map<uint32_t, double> reprojection = MeanReprojectionErrors(model);
  const std::vector<const Image*> images = ImagesInCaptureOrder(model);
  std::vector<std::string> names;
  nlohmann::json names_json = nlohmann::json::array(), centers = nlohmann::json::array(),
                 rotations = nlohmann::json::array(), fields = nlohmann::json::array(),
                 rotation_errors = nlohmann::json::array(),
                 position_errors = nlohmann::json::array(),
                 reprojection_errors = nlohmann::json::array();
  const int d = options.digits;
  for (const Image* image : images) {
    names.push_back(image->name);
    names_json.push_back(image->name);
    const Rigid3d pose = TransformPose(reference_from_model, image->cam_from_world);
    const Rigid3d world_from_cam = pose.Inverse();
    AppendVector(world_from_cam.translation - options.origin, d, &centers);
    const Eigen::Quaterniond q = world_from_cam.rotation.normalized();
    for (const double c : {q.x(), q.y(), q.z(), q.w()}) rotations.push_back(Rounded(c, d));
    const auto camera = model.cameras.find(image->camera_id);
    const Eigen::Vector2d half = camera == model.cameras.end() ? Eigen::Vector2d(0.5, 0.375)
                                                               : HalfFieldOfView(camera->second);
    fields.push_back(Rounded(half.x(), 4));
    fields.push_back(Rounded(half.y(), 4));
    const auto error = errors.find(image->name);
    const bool scored = error != errors.end() && error->second->rotation_error_deg >= 0;
    rotation_errors.push_back(scored ? Rounded(error->second->rotation_error_deg, 4) : nullptr);
    position_errors.push_back(scored ? Rounded(error->second->position_error, 4) : nullptr);
    const auto mean = reprojection.find(image->image_id);
    reprojection_errors.push_back(mean == reprojection.end() ? nlohmann::json()
                                                             : Rounded(mean->second, 4));
  }
  return {{"name", name},
          {"num_registered", images.size()},
          {"sequence", LooksSequential(names)},
          {"images",
           {{"name", names_json},
            {"center", centers},
            {"rotation", rotations},
            {"half_fov", fields},
            {"rotation_error_deg", evaluation != nullptr ? rotation_errors : nlohmann::json()},
            {"position_error", evaluation != nullptr ? position_errors : nlohmann::json()},
            {"reprojection_error_px", reprojection_errors}}},
          {"points", PointsJson(model, reference_from_model, options.origin, max_points, d)}};
}

nlohmann::json ReportReferenceJson(const std::string& name,
                                   const std::map<std::string, Rigid3d>& poses,
                                   const Reconstruction* like, const ReportSceneOptions& options) {
  const Camera camera =
      like != nullptr && !like->cameras.empty()
          ? like->cameras.begin()->second
          : Camera{1, CameraModel::kSimplePinhole, 640, 480, {500, 320, 240}, false};
  const Reconstruction model = ModelOfPoses(poses, camera);
  nlohmann::json json = ReportModelJson(name, model, Sim3d(), nullptr, 0, options);
  json["images"]["reprojection_error_px"] = nullptr;
  return json;
}

nlohmann::json ReportRecallCurveJson(const std::string& name, const PoseEvaluation& evaluation) {
  nlohmann::json thresholds = nlohmann::json::array(), recall = nlohmann::json::array();
  for (size_t k = 0; k < evaluation.recall_curve.size(); ++k) {
    thresholds.push_back(Rounded(evaluation.recall_curve_thresholds_deg[k], 4));
    recall.push_back(Rounded(evaluation.recall_curve[k], 4));
  }
  nlohmann::json auc = nlohmann::json::object();
  for (size_t k = 0; k < evaluation.auc.size(); ++k) {
    char key[16];
    std::snprintf(key, sizeof(key), "%g", evaluation.auc_thresholds_deg[k]);
    auc[key] = Rounded(100 * evaluation.auc[k], 4);
  }
  return {{"name", name}, {"threshold_deg", thresholds}, {"recall", recall}, {"auc", auc}};
}

}  // namespace ramap
