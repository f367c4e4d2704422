#include "ramap/jobs/mapper_output.h"

#include <fcntl.h>
#include <stdio.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <future>
#include <system_error>

#include "ramap/io/geo_export.h"
#include "ramap/io/trajectory.h"
#include "ramap/report/html_report.h"
#include "ramap/report/mapper_page.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"
#include "ramap/util/staged_output.h"

namespace ramap {
namespace fs = std::filesystem;

namespace {

// Each camera: as given, as the view graph estimated it (or why not), as written.
nlohmann::json CamerasToJson(const std::vector<CameraIntrinsicsSummary>& summaries) {
  nlohmann::json cameras = nlohmann::json::array();
  for (const CameraIntrinsicsSummary& camera : summaries) {
    nlohmann::json entry = {{"camera_id", camera.camera_id},
                            {"model", camera.model},
                            {"prior_focal_length_known", camera.prior_focal_length_known},
                            {"prior_params", camera.prior_params},
                            {"focal_source", camera.focal_source},
                            {"final_params", camera.final_params}};
    if (!camera.final_model.empty() && camera.final_model != camera.model)
      entry["final_model"] = camera.final_model;
    const CameraCalibration& estimate = camera.view_graph;
    if (estimate.camera_id != 0) {
      entry["view_graph_calibration"] = {{"estimated", estimate.estimated},
                                         {"given", estimate.given},
                                         {"outcome", FocalOutcomeName(estimate.outcome)},
                                         {"prior_focal_px", estimate.prior_focal_px},
                                         {"estimated_focal_px", estimate.estimated_focal_px},
                                         {"num_pairs", estimate.num_pairs},
                                         {"median_cost", estimate.median_cost},
                                         {"problem", estimate.problem}};
    }
    cameras.push_back(entry);
  }
  return cameras;
}

// Rotation averaging's phases, in seconds (RotationAveragingTimings).
nlohmann::json RotationSecondsJson(const RotationAveragingTimings& seconds) {
  return {{"windows", seconds.windows}, {"init", seconds.init},
          {"l1", seconds.l1},           {"irls", seconds.irls},
          {"pruning", seconds.pruning}, {"certificate", seconds.certificate},
          {"total", seconds.total}};
}

// One component: its model, how its rotations and positions were averaged, its bundle
// adjustment and prior alignment when run.
// Each group of cameras with given intrinsics: what each step of the test measured and kept.
nlohmann::json GivenIntrinsicsTestJson(const GivenIntrinsicsTestSummary& test) {
  nlohmann::json groups = nlohmann::json::array();
  for (const GivenIntrinsicsTest& g : test.groups) {
    nlohmann::json group = {{"camera_ids", g.camera_ids},
                            {"num_images", g.num_images},
                            {"num_observations", g.num_observations},
                            {"given_model", g.given_model},
                            {"given_focal_px", g.given_focal_px},
                            {"held_rmse_px", g.held_rmse_px},
                            {"distortion_tried", g.distortion_tried},
                            {"freed_focal_px", g.freed_focal_px},
                            {"freed_rmse_px", g.freed_rmse_px},
                            {"focal_accepted", g.focal_accepted},
                            {"distortion_accepted", g.distortion_accepted},
                            {"final_model", g.final_model}};
    if (g.focal_only_rmse_px > 0) group["focal_only_rmse_px"] = g.focal_only_rmse_px;
    groups.push_back(group);
  }
  return {{"groups", groups}, {"seconds", test.seconds}};
}

nlohmann::json BundleAdjustmentToJson(const MapperComponentSummary& c) {
  const BundleAdjustmentSummary& ba = c.bundle_adjustment;
  nlohmann::json filtered = nlohmann::json::array();
  for (const auto& [name, count] : c.most_filtered_images)
    filtered.push_back({{"name", name}, {"num_filtered_observations", count}});
  return {{"initial_rmse_px", ba.initial_rmse_px},
          {"final_rmse_px", ba.final_rmse_px},
          {"num_iterations", ba.num_iterations},
          {"num_filtered_observations", ba.num_filtered_observations},
          {"num_solves", ba.num_solves},
          {"wide_start_loss_px", ba.wide_start_loss_px},
          {"converged", ba.converged},
          {"poses_settled", ba.poses_settled},
          {"seconds", ba.seconds},
          {"most_filtered_images", filtered}};
}

nlohmann::json ComponentToJson(const MapperComponentSummary& c) {
  nlohmann::json component = {
      {"num_images", c.num_images},
      {"num_points", c.num_points},
      {"num_observations", c.num_observations},
      {"mean_reprojection_error_px", c.mean_reprojection_error_px},
      {"rotation_averaging",
       {{"num_edges", c.num_rotation_edges},
        {"num_pruned_edges", c.num_pruned_edges},
        {"certified_globally_optimal", c.rotation_certified},
        {"certificate_bound_deg", c.certificate_bound_deg},
        {"certificate_cycle_lower_bound_deg", c.certificate_cycle_lower_bound_deg},
        {"max_residual_deg", c.max_rotation_residual_deg},
        {"num_factorizations", c.num_rotation_factorizations},
        {"seconds", RotationSecondsJson(c.rotation_seconds)}}},
      {"translation_averaging",
       {{"num_rejected_directions", c.num_rejected_directions},
        {"direction_median_residual_deg", c.direction_median_residual_deg},
        {"direction_threshold_deg", c.direction_threshold_deg},
        {"num_rejected_rows", c.num_rejected_translation_rows},
        {"num_constraints", c.num_translation_constraints},
        {"num_solver_iterations", c.num_solver_iterations},
        {"num_factorizations", c.num_factorizations},
        {"num_windows", c.num_translation_windows}}},
  };
  if (c.bundle_adjustment.num_observations > 0)
    component["bundle_adjustment"] = BundleAdjustmentToJson(c);
  if (!c.reregistered_images.empty()) {
    nlohmann::json images = nlohmann::json::array();
    for (const ReregisteredImage& image : c.reregistered_images) {
      images.push_back({{"name", image.name},
                        {"num_correspondences", image.num_correspondences},
                        {"num_inliers_before", image.num_inliers_before},
                        {"num_inliers_after", image.num_inliers_after},
                        {"rotation_change_deg", image.rotation_change_deg},
                        {"replaced", image.replaced}});
    }
    component["reregistered_images"] = images;
  }
  if (!c.given_intrinsics_test.groups.empty())
    component["given_intrinsics_test"] = GivenIntrinsicsTestJson(c.given_intrinsics_test);
  const PriorAlignmentSummary& geo = c.prior_alignment;
  if (geo.num_priors > 0 || !geo.problem.empty()) {
    nlohmann::json outliers = nlohmann::json::array();
    for (const PriorOutlier& o : geo.outliers) {
      outliers.push_back({{"image_id", o.image_id}, {"error_m", o.error_m}});
    }
    component["prior_alignment"] = {
        {"aligned", geo.aligned},
        {"problem", geo.problem},
        {"num_priors", geo.num_priors},
        {"num_inliers", geo.num_inliers},
        {"rmse_m", geo.rmse_m},
        {"threshold_m", geo.threshold_m},
        {"metres_per_model_unit", geo.scale},
        {"used_in_translation_averaging", geo.used_in_translation_averaging},
        {"used_in_bundle_adjustment", geo.used_in_bundle_adjustment},
        {"outliers", outliers}};
    // The block's former name and first key, kept as an alias for readers of earlier summaries
    // (README, "Renamed").
    nlohmann::json former = component["prior_alignment"];
    former.erase("aligned");
    former["georegistered"] = geo.aligned;
    component["georegistration"] = std::move(former);
  }
  return component;
}

}  // namespace

// The frame and scale the models are written in, as summary.json states them.
constexpr const char* kGauge =
    "translation averaging: the first registered image of each component at the origin, mean "
    "projected pair baseline 1; bundle adjustment (when run) holds the first image fixed; a "
    "component aligned to its pose priors is in their metric frame instead (east-north-up about "
    "geo_origin.txt when the priors are geodetic)";

nlohmann::json MapperSummaryToJson(const MapperSummary& summary) {
  nlohmann::json json;
  json["num_images"] = summary.num_images;
  json["num_averaging_passes"] = summary.num_averaging_passes;
  json["first_pass_only_calibrated"] = summary.calibration_pass;
  json["num_registered_images"] = summary.num_registered_images;
  json["num_verified_pairs"] = summary.num_verified_pairs;
  json["num_relative_poses"] = summary.num_relative_poses;
  json["sequential"] = summary.sequential;
  json["num_keyframes"] = summary.num_keyframes;
  json["num_loop_edges"] = summary.num_loop_edges;
  json["total_seconds"] = summary.total_seconds;
  json["peak_rss_mib"] = summary.peak_rss_mib;
  json["gauge"] = kGauge;
  for (const MapperStageTiming& timing : summary.timings)
    json["stage_seconds"][timing.stage] = timing.seconds;
  for (const MapperComponentSummary& component : summary.components)
    json["components"].push_back(ComponentToJson(component));
  json["cameras"] = CamerasToJson(summary.cameras);
  json["dropped_images"] = nlohmann::json::array();
  for (const DroppedItem& item : summary.dropped_images) {
    json["dropped_images"].push_back({{"image", item.what}, {"reason", item.reason}});
  }
  json["prior_outliers"] = nlohmann::json::array();
  for (const DroppedItem& item : summary.prior_outliers) {
    json["prior_outliers"].push_back({{"image", item.what}, {"reason", item.reason}});
  }
  json["dropped_edges"] = nlohmann::json::array();
  for (const DroppedItem& item : summary.dropped_edges) {
    json["dropped_edges"].push_back({{"pair", item.what}, {"reason", item.reason}});
  }
  return json;
}

namespace {

// The stages' seconds in the order they ran (each stage once: the log sums its passes).
std::vector<std::pair<std::string, double>> StageSeconds(const MapperSummary& summary) {
  std::vector<std::pair<std::string, double>> stages;
  for (const MapperStageTiming& timing : summary.timings) {
    stages.push_back({timing.stage, timing.seconds});
  }
  return stages;
}

// The data set's name, as the folder of its database.
std::string PageTitle(const nlohmann::json& run_info) {
  if (!run_info.is_object()) return "ramap mapper";
  const std::string database = run_info.value("database_path", std::string());
  if (database.empty()) return "ramap mapper";
  const std::string name = fs::absolute(database).parent_path().filename().string();
  return name.empty() ? "ramap mapper" : name;
}

void WriteContents(const MapperResult& result, const std::string& folder, ModelFormat format,
                   const nlohmann::json& run_info, std::ostream* warnings, int num_threads) {
  fs::create_directories(folder);
  nlohmann::json summary = MapperSummaryToJson(result.summary);
  summary["run"] = run_info;
  // The page is for looking at the run; the models are the result. A page that cannot be made
  // costs a warning, never the models. Its point cloud takes as long to build as the models take
  // to write, so with a thread to spare the two go side by side (the future waits when it goes).
  std::string page_problem;
  std::future<void> page =
      std::async(num_threads > 1 ? std::launch::async : std::launch::deferred, [&] {
        try {
          WriteHtmlReport(MapperPageData(result.reconstructions, summary,
                                         StageSeconds(result.summary), PageTitle(run_info)),
                          folder + "/report.html");
        } catch (const std::exception& error) {
          page_problem = error.what();
        }
      });
  for (size_t k = 0; k < result.reconstructions.size(); ++k) {
    const std::string model_path = folder + "/" + std::to_string(k);
    WriteColmapModel(result.reconstructions[k], model_path, format);
    WriteTumTrajectory(result.reconstructions[k], model_path + "/trajectory_tum.txt");
    const bool aligned = k < result.summary.components.size() &&
                         result.summary.components[k].prior_alignment.aligned;
    if (aligned && result.geodetic_origin) {
      WriteGeoreference(result.reconstructions[k], *result.geodetic_origin, model_path);
    }
  }
  WriteFileAtomically(folder + "/summary.json",
                      [&](std::ostream& out) { out << summary.dump(2) << "\n"; });
  page.get();
  if (!page_problem.empty() && warnings != nullptr)
    *warnings << "ramap: warning: report.html not written: " << page_problem << "\n";
}

// Puts `from` at `to`: a plain rename when nothing is there, else an atomic exchange of the two
// (Linux's renameat2 RENAME_EXCHANGE), so that `to` is never missing; where the filesystem cannot
// exchange, the old entry is removed first and `to` is missing for a moment.
bool MoveIntoPlace(const fs::path& from, const fs::path& to, std::string* problem) {
  std::error_code ec;
  if (fs::exists(fs::symlink_status(to, ec))) {
    if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_EXCHANGE) == 0) {
      return true;
    }
    if (errno != EINVAL && errno != ENOSYS) {
      *problem = std::strerror(errno);
      return false;
    }
    fs::remove_all(to, ec);
  }
  fs::rename(from, to, ec);
  if (ec) *problem = ec.message();
  return !ec;
}

}  // namespace

void WriteMapperOutput(const MapperResult& result, const std::string& output_path,
                       ModelFormat format, const nlohmann::json& run_info, std::ostream* warnings,
                       int num_threads) {
  if (!fs::exists(output_path)) {
    // A new folder appears whole, by one rename.
    StagedPath staged(output_path);
    WriteContents(result, staged.path(), format, run_info, warnings, num_threads);
    staged.Commit();
    return;
  }
  if (!fs::is_directory(output_path)) throw InputError(output_path, "exists and is not a folder");
  // An existing folder (perhaps holding the user's other files) gets each entry moved in once
  // everything has been written beside it. Only model folders, summary.json and ramap's own
  // report.html are replaced, and only after every one of them has been checked.
  std::vector<fs::path> replaced;
  auto check_model_target = [&](const fs::path& target) {
    std::string foreign;
    if (!IsReplaceableModelFolder(target.string(), &foreign)) {
      throw InputError(output_path, "cannot replace " + target.string() + ": it holds " + foreign +
                                        ", which ramap did not write (move it, or choose "
                                        "another --output_path)");
    }
  };
  for (size_t k = 0;; ++k) {
    const fs::path target = fs::path(output_path) / std::to_string(k);
    std::error_code ec;
    const bool exists = fs::exists(fs::symlink_status(target, ec));
    const bool stale = k >= result.reconstructions.size();
    if (!exists) {
      if (stale) break;
      continue;
    }
    if (stale && !fs::exists(target / "cameras.bin") && !fs::exists(target / "cameras.txt")) break;
    check_model_target(target);
    replaced.push_back(target);
  }
  for (const char* file : {"summary.json", "report.html"}) {
    if (fs::is_directory(fs::path(output_path) / file)) {
      throw InputError(output_path,
                       std::string(file) + " there is a folder; ramap does not replace it");
    }
  }
  const fs::path report = fs::path(output_path) / "report.html";
  if (fs::exists(report) && !IsRamapReport(report.string())) {
    throw InputError(report.string(),
                     "ramap did not write this page and does not replace it (move it, or choose "
                     "another --output_path)");
  }
  StagedPath staged(output_path + "/.ramap-output");
  WriteContents(result, staged.path(), format, run_info, warnings, num_threads);
  // Each new entry takes its old one's place in one atomic exchange, the old one going to the
  // staged folder that is removed after: an interrupt at any moment leaves every model whole,
  // either the earlier run's or this one's, never neither.
  std::vector<fs::path> swapped;
  for (const auto& entry : fs::directory_iterator(staged.path())) {
    const fs::path target = fs::path(output_path) / entry.path().filename();
    std::string problem;
    if (!MoveIntoPlace(entry.path(), target, &problem)) {
      throw InputError(output_path, "cannot move " + target.string() + " into place: " + problem);
    }
    swapped.push_back(target);
  }
  // Models of the earlier run beyond this run's count go last.
  std::error_code ec;
  for (const fs::path& target : replaced) {
    if (std::find(swapped.begin(), swapped.end(), target) == swapped.end()) {
      fs::remove_all(target, ec);
    }
  }
}

}  // namespace ramap
