#include "ramap/compare/comparison_figures.h"

#include <algorithm>
#include <limits>

#include "ramap/compare/plots.h"
#include "ramap/geometry/alignment.h"
#include "ramap/scene/image_order.h"

namespace ramap {
namespace {

// Camera centres of `poses` in `names` order, mapped by `transform`.
std::vector<Eigen::Vector3d> Centers(const std::map<std::string, Rigid3d>& poses,
                                     const std::vector<std::string>& names,
                                     const Sim3d& transform) {
  std::vector<Eigen::Vector3d> centers;
  for (const std::string& name : names) {
    const auto it = poses.find(name);
    if (it == poses.end()) continue;
    centers.push_back(transform * (it->second.Inverse().translation));
  }
  return centers;
}

}  // namespace

std::vector<StageBar> StageBars(const std::vector<MapperRun>& runs) {
  std::vector<StageBar> bars;
  for (const MapperRun& run : runs) {
    if (!run.succeeded) continue;
    StageBar bar{run.name, run.stage_seconds};
    double staged = 0;
    for (const auto& [stage, seconds] : run.stage_seconds) staged += seconds;
    bar.stages.push_back({run.stage_seconds.empty() ? "whole mapper" : "input / output",
                          std::max(0.0, run.seconds - staged)});
    bars.push_back(bar);
  }
  return bars;
}

void DrawComparisonFigures(const std::vector<std::string>& names,
                           const std::map<std::string, Rigid3d>& reference, bool against_colmap,
                           const std::map<std::string, std::map<std::string, Rigid3d>>& poses,
                           const std::string& title, const std::string& output_path,
                           Comparison* comparison) {
  std::vector<std::string> capture_order;
  for (const size_t k : CaptureOrder(names)) capture_order.push_back(names[k]);
  std::vector<PlotSeries> trajectories = {{against_colmap ? "COLMAP (reference)" : "ground truth",
                                           Centers(reference, capture_order, Sim3d()),
                                           {}}};
  std::vector<PlotSeries> rotation_errors, position_errors;
  for (const MapperRun& run : comparison->runs) {
    if (!run.evaluation) continue;
    trajectories.push_back(
        {run.name,
         Centers(poses.at(run.name), capture_order, run.evaluation->gt_from_estimate),
         {}});
    PlotSeries rotations{run.name, {}, {}}, positions{run.name, {}, {}};
    for (const ImageEvaluation& image : run.evaluation->images) {
      if (!image.has_ground_truth) continue;
      const double inf = std::numeric_limits<double>::infinity();
      rotations.values.push_back(image.registered ? image.rotation_error_deg : inf);
      positions.values.push_back(image.registered ? image.position_error : inf);
    }
    rotation_errors.push_back(rotations);
    position_errors.push_back(positions);
  }
  if (trajectories.size() > 1) {
    PlotTrajectories(trajectories, "Camera centres, top-down (" + title + ")",
                     output_path + "/trajectories.png");
    PlotCumulativeDistributions(rotation_errors, "Rotation error after alignment (" + title + ")",
                                "degrees", output_path + "/rotation_error_cdf.png");
    PlotCumulativeDistributions(position_errors, "Position error after alignment (" + title + ")",
                                against_colmap ? "COLMAP model units" : "ground-truth units",
                                output_path + "/position_error_cdf.png");
    comparison->figures = {"trajectories.png", "rotation_error_cdf.png", "position_error_cdf.png"};
  }
  PlotStageTimes(StageBars(comparison->runs), "Wall time per stage, seconds (" + title + ")",
                 output_path + "/stage_times.png");
  comparison->figures.push_back("stage_times.png");
}

}  // namespace ramap
