// What report.html draws, as plain JSON for its script: each model's cameras (centre, rotation,
// field of view, errors) in capture order and a subsample of its points, brought into the frame of
// the reference; the reference's own cameras; each evaluation's recall curve.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "ramap/eval/pose_metrics.h"
#include "ramap/geometry/alignment.h"
#include "ramap/scene/reconstruction.h"
#include "ramap/scene/rigid3.h"

namespace ramap {

struct ReportSceneOptions {
  // Points drawn at most, over all models of a report: a fixed budget keeps the page small and
  // quick to open however large the models (docs/benchmark-history.md, "report.html").
  size_t max_points = 120000;
  // Significant digits of coordinates in the page (millimetres on a kilometre-sized scene).
  int digits = 7;
  // Coordinates are written relative to this point (SceneMiddle), so that those digits and the
  // browser's 32-bit floats keep their precision in a scene far from its frame's origin (UTM).
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
};

// The mean camera centre of `model`, brought by `transform`: the page's origin.
Eigen::Vector3d SceneMiddle(const Reconstruction& model, const Sim3d& transform = Sim3d());

// One model for the page: `reference_from_model` brings it into the reference's frame (identity
// without one); `evaluation`, when given, supplies each image's rotation and position error; each
// image's mean reprojection error is computed from the model's tracks. `max_points` of its points
// at most, evenly spread over its point ids.
nlohmann::json ReportModelJson(const std::string& name, const Reconstruction& model,
                               const Sim3d& reference_from_model, const PoseEvaluation* evaluation,
                               size_t max_points,
                               const ReportSceneOptions& options = ReportSceneOptions());

// Reference cameras without a model (ground truth): poses by image name; each drawn with the
// field of view of `like`'s first camera (ground truth has no intrinsics).
nlohmann::json ReportReferenceJson(const std::string& name,
                                   const std::map<std::string, Rigid3d>& poses,
                                   const Reconstruction* like,
                                   const ReportSceneOptions& options = ReportSceneOptions());

// The evaluation's recall of image pairs against the error threshold (PoseEvaluation's curve).
nlohmann::json ReportRecallCurveJson(const std::string& name, const PoseEvaluation& evaluation);

}  // namespace ramap
