// `ramap compare --database_path DB --output_path DIR [--image_path DIR] [--ground_truth PATH
// --ground_truth_format FORMAT]`: COLMAP's BA mapper and ramap's averaging mapper, with and without
// --Mapper.refine 1, on the same database. Each mapper runs as its own process and is timed as a
// whole; each largest model is evaluated against the ground truth (or, without one, the ramap
// models against COLMAP's). Writes DIR/report.md, DIR/report.json and figures in DIR.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "options.h"
#include "ramap/eval/comparison.h"
#include "ramap/eval/plots.h"
#include "ramap/geometry/camera_projection.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "ramap/io/trajectory.h"
#include "ramap/pipeline/image_order.h"
#include "ramap/pipeline/stage_log.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"
#include "ramap/util/staged_output.h"

namespace ramap::cli {
namespace {

namespace fs = std::filesystem;

std::string Quote(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// Runs `command` with its output in `log_path`; returns the wall time and whether it exited 0.
std::pair<double, bool> RunTimed(const std::string& command, const std::string& log_path) {
  const auto start = std::chrono::steady_clock::now();
  const int status = std::system((command + " > " + Quote(log_path) + " 2>&1").c_str());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return {seconds, status == 0};
}

// The numbered model folder under `output_path` with the most images.
void PickLargestModel(const std::string& output_path, MapperRun* run) {
  if (!fs::is_directory(output_path)) return;
  size_t best = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(output_path)) {
    if (!entry.is_directory()) continue;
    try {
      const size_t size = ReadColmapModel(entry.path().string()).images.size();
      ++run->num_models;
      if (size > best) best = size, run->model_path = entry.path().string();
    } catch (const InputError&) {
      // Not a model (ramap's staging folders, a half-written COLMAP snapshot).
    }
  }
  run->num_registered = static_cast<int>(best);
}

// Stage seconds from ramap's summary.json, in the order the stages ran.
std::vector<std::pair<std::string, double>> StageSeconds(const std::string& summary_path) {
  std::vector<std::pair<std::string, double>> stages;
  std::ifstream in(summary_path);
  if (!in) return stages;
  const nlohmann::json summary = nlohmann::json::parse(in, nullptr, false);
  if (summary.is_discarded() || !summary.contains("stage_seconds")) return stages;
  for (const std::string& stage : TimedMapperStages()) {
    if (summary["stage_seconds"].contains(stage)) {
      stages.push_back({stage, summary["stage_seconds"][stage].get<double>()});
    }
  }
  return stages;
}

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

// Each run's folder is replaced whole, so it may hold only an earlier run's output; checked for
// every run before the first one starts.
void CheckRunFolder(const std::string& output_path, const std::string& run_folder) {
  const std::string folder = output_path + "/" + run_folder;
  std::string foreign;
  if (fs::exists(fs::symlink_status(folder)) && !IsReplaceableMapperOutput(folder, &foreign)) {
    throw InputError("--output_path " + output_path,
                     folder + " holds " + foreign +
                         ", which is not an earlier compare run's output; choose another "
                         "--output_path");
  }
  if (fs::is_directory(folder + ".log")) {
    throw InputError("--output_path " + output_path, folder + ".log is a folder");
  }
}

// The report is written (it says which run failed), but the comparison is incomplete.
void ThrowIfAnyRunFailed(const Comparison& comparison, const std::string& output_path) {
  std::string failed;
  for (const MapperRun& run : comparison.runs) {
    if (!run.succeeded) failed += (failed.empty() ? "" : ", ") + run.name;
  }
  if (!failed.empty()) {
    throw InputError("ramap compare", failed + " failed; see the .log files in " + output_path);
  }
}

struct Plan {
  std::string name, folder, command;
};

// The three mapper runs on one database as command lines: COLMAP, ramap averaging alone, ramap
// with BA. Without refine_intrinsics every mapper keeps the intrinsics fixed (COLMAP's and ramap's
// options of the same meaning).
std::vector<Plan> MapperPlans(const std::string& colmap, const std::string& database_path,
                              const std::string& images, const std::string& output_path,
                              int num_threads, bool refine_intrinsics) {
  const std::string colmap_intrinsics =
      refine_intrinsics ? ""
                        : " --Mapper.ba_refine_focal_length 0 --Mapper.ba_refine_principal_point 0"
                          " --Mapper.ba_refine_extra_params 0";
  const std::string ramap_intrinsics = refine_intrinsics
                                           ? ""
                                           : " --BundleAdjustment.refine_focal_length 0"
                                             " --BundleAdjustment.refine_principal_point 0"
                                             " --BundleAdjustment.refine_extra_params 0";
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  const std::string threads = std::to_string(num_threads);
  auto ramap = [&](const std::string& folder, const std::string& options) {
    return Quote(self) + " mapper --database_path " + Quote(database_path) + " --output_path " +
           Quote(output_path + "/" + folder) + " --Mapper.num_threads " + threads + options;
  };
  return {
      {"COLMAP", "colmap",
       Quote(colmap) + " mapper --database_path " + Quote(database_path) + " --image_path " +
           Quote(images) + " --output_path " + Quote(output_path + "/colmap") +
           " --Mapper.num_threads " + threads + colmap_intrinsics},
      {"ramap", "ramap", ramap("ramap", " --Mapper.refine 0")},
      {"ramap+BA", "ramap_ba", ramap("ramap_ba", " --Mapper.refine 1" + ramap_intrinsics)},
  };
}

// Runs `plan` in its folder (replaced), timed as a process; the poses of its largest model go to
// `poses` under the run's name.
MapperRun RunPlan(const Plan& plan, const std::string& output_path, size_t num_images,
                  std::map<std::string, std::map<std::string, Rigid3d>>* poses) {
  const std::string folder = output_path + "/" + plan.folder;
  fs::remove_all(folder);
  fs::create_directories(folder);
  std::cout << "[ramap compare] " << plan.name << ": " << plan.command << std::endl;
  MapperRun run;
  run.name = plan.name;
  run.command = plan.command;
  const auto [seconds, exited_cleanly] = RunTimed(plan.command, folder + ".log");
  run.seconds = seconds;
  PickLargestModel(folder, &run);
  run.succeeded = exited_cleanly && !run.model_path.empty();
  if (!run.succeeded) {
    std::cerr << "ramap compare: " << plan.name << " failed (see " << folder << ".log)\n";
  } else {
    const Reconstruction model = ReadColmapModel(run.model_path);
    (*poses)[run.name] = PosesByName(model, run.model_path);
    for (const auto& [camera_id, camera] : model.cameras) {
      run.focal_lengths_px[camera_id] = MeanFocalLength(camera);
    }
  }
  run.stage_seconds = StageSeconds(folder + "/summary.json");
  std::cout << "[ramap compare] " << plan.name << ": " << run.num_registered << " of " << num_images
            << " images in " << seconds << " s" << std::endl;
  return run;
}

// Each run's bar: its stages, and what they do not cover (reading the database, writing the
// model; all of COLMAP's time).
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

// The figures in output_path, their file names added to comparison->figures: a top-down overlay
// of the camera centres, rotation and position error distributions, stage times. `name` is the
// data set's.
void DrawFigures(const std::vector<std::string>& names,
                 const std::map<std::string, Rigid3d>& reference, bool against_colmap,
                 const std::map<std::string, std::map<std::string, Rigid3d>>& poses,
                 const std::string& name, const std::string& output_path, Comparison* comparison) {
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
    PlotTrajectories(trajectories, "Camera centres, top-down (" + name + ")",
                     output_path + "/trajectories.png");
    PlotCumulativeDistributions(rotation_errors, "Rotation error after alignment (" + name + ")",
                                "degrees", output_path + "/rotation_error_cdf.png");
    PlotCumulativeDistributions(position_errors, "Position error after alignment (" + name + ")",
                                against_colmap ? "COLMAP model units" : "ground-truth units",
                                output_path + "/position_error_cdf.png");
    comparison->figures = {"trajectories.png", "rotation_error_cdf.png", "position_error_cdf.png"};
  }
  PlotStageTimes(StageBars(comparison->runs), "Wall time per stage, seconds (" + name + ")",
                 output_path + "/stage_times.png");
  comparison->figures.push_back("stage_times.png");
}

// report.json and report.md in output_path; the Markdown is printed too.
void WriteReports(const Comparison& comparison, const std::string& output_path) {
  WriteFileAtomically(output_path + "/report.json", [&](std::ostream& out) {
    out << ComparisonToJson(comparison).dump(2) << "\n";
  });
  const std::string markdown = ComparisonToMarkdown(comparison);
  WriteFileAtomically(output_path + "/report.md", [&](std::ostream& out) { out << markdown; });
  std::cout << "\n" << markdown;
}

}  // namespace

int RunCompare(int argc, char** argv) {
  CLI::App app(
      "COLMAP's BA mapper vs ramap's averaging mapper (with and without BA) on one database: "
      "accuracy, time and figures.",
      "ramap compare");
  std::string database_path, image_path, output_path, ground_truth_path, ground_truth_format;
  std::string colmap = "colmap";
  bool refine_intrinsics = false;
  int num_threads = 2;
  app.add_option("--database_path", database_path, "COLMAP database with verified matches")
      ->required();
  app.add_option("--output_path", output_path, "folder for the models, logs, report and figures")
      ->required();
  app.add_option("--image_path", image_path, "the images (colours; COLMAP's mapper wants one)");
  app.add_option("--ground_truth", ground_truth_path, "ground-truth file or folder");
  app.add_option("--ground_truth_format", ground_truth_format,
                 "tum, kitti, strecha, middlebury or colmap");
  app.add_option("--colmap_path", colmap, "the colmap binary")->capture_default_str();
  app.add_option("--Compare.refine_intrinsics", refine_intrinsics,
                 "0: intrinsics fixed in every mapper (fair with known calibration); 1: refined")
      ->capture_default_str();
  app.add_option("--Compare.num_threads", num_threads, "threads of every mapper")
      ->capture_default_str()
      ->check(AtLeast(1, 256));
  if (const std::optional<int> code = ParseOptions(app, argc, argv)) return *code;
  if (ground_truth_path.empty() != ground_truth_format.empty()) {
    throw InputError("--ground_truth", "give both --ground_truth and --ground_truth_format");
  }
  CheckFolderOutput("--output_path", output_path, {database_path, image_path, ground_truth_path});

  const std::vector<std::string> names = ReadDatabaseImageNames(database_path);
  std::map<std::string, Rigid3d> gt_poses;
  if (!ground_truth_path.empty()) {
    gt_poses = GroundTruthByImageName(
        ReadGroundTruth(ground_truth_path, GroundTruthFormatFromName(ground_truth_format)), names);
    if (gt_poses.empty()) {
      throw InputError(ground_truth_path, "no image of the database has a ground-truth pose");
    }
  }

  const std::string images = image_path.empty() ? output_path + "/no_images" : image_path;
  const std::vector<Plan> plans =
      MapperPlans(colmap, database_path, images, output_path, num_threads, refine_intrinsics);

  for (const Plan& plan : plans) CheckRunFolder(output_path, plan.folder);
  fs::create_directories(output_path);
  fs::create_directories(images);

  Comparison comparison;
  comparison.database_path = database_path;
  comparison.num_images = static_cast<int>(names.size());
  comparison.reference =
      ground_truth_path.empty()
          ? std::string("the COLMAP model (no ground truth given)")
          : "ground truth " + ground_truth_path + " (" + ground_truth_format + ")";
  std::map<std::string, std::map<std::string, Rigid3d>> poses;  // by run name
  for (const Plan& plan : plans) {
    comparison.runs.push_back(RunPlan(plan, output_path, names.size(), &poses));
  }

  // Evaluation against the ground truth, or against COLMAP's model.
  const bool against_colmap = gt_poses.empty();
  const std::map<std::string, Rigid3d> reference =
      against_colmap && poses.count("COLMAP") ? poses.at("COLMAP") : gt_poses;
  for (MapperRun& run : comparison.runs) {
    if (!run.succeeded || reference.empty() || (against_colmap && run.name == "COLMAP")) continue;
    run.evaluation = EvaluatePoses(poses.at(run.name), reference, names);
  }

  // The data set's name, as the folder of its database.
  const std::string name = fs::absolute(database_path).parent_path().filename().string();
  DrawFigures(names, reference, against_colmap, poses, name, output_path, &comparison);

  WriteReports(comparison, output_path);
  ThrowIfAnyRunFailed(comparison, output_path);
  return 0;
}

}  // namespace ramap::cli
