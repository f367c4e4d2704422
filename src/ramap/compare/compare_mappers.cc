#include "ramap/compare/compare_mappers.h"

#include <filesystem>
#include <iostream>

#include "ramap/compare/comparison_figures.h"
#include "ramap/compare/comparison_page.h"
#include "ramap/compare/mapper_plans.h"
#include "ramap/compare/mapper_process.h"
#include "ramap/eval/pose_metrics.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/trajectory.h"
#include "ramap/util/error.h"
#include "ramap/util/option_check.h"
#include "ramap/util/output_policy.h"
#include "ramap/util/staged_output.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

using PosesByRun = std::map<std::string, std::map<std::string, Rigid3d>>;

void CheckOptions(const CompareOptions& options) {
  if (options.ground_truth_path.empty() != options.ground_truth_format.empty()) {
    throw InputError("--ground_truth", "give both --ground_truth and --ground_truth_format");
  }
  CheckOptionValues(CompareOptionTable(), options);
  CheckFolderOutput("--output_path", options.output_path,
                    {options.database_path, options.image_path, options.ground_truth_path});
}

// The ground-truth poses of the database's images, by name; empty without ground truth.
std::map<std::string, Rigid3d> GroundTruthPoses(const CompareOptions& options,
                                                const std::vector<std::string>& names) {
  if (options.ground_truth_path.empty()) return {};
  std::map<std::string, Rigid3d> poses = GroundTruthByImageName(
      ReadGroundTruth(options.ground_truth_path,
                      GroundTruthFormatFromName(options.ground_truth_format)),
      names);
  if (poses.empty()) {
    throw InputError(options.ground_truth_path, "no image of the database has a ground-truth pose");
  }
  return poses;
}

// Every run against `reference`, but the reference run itself when it is COLMAP's model.
void EvaluateRuns(const std::map<std::string, Rigid3d>& reference, bool against_colmap,
                  const PosesByRun& poses, const std::vector<std::string>& names,
                  Comparison* comparison) {
  for (MapperRun& run : comparison->runs) {
    if (!run.succeeded || reference.empty() ||
        (against_colmap && run.name == mapper_row::kColmap)) {
      continue;
    }
    run.evaluation = EvaluatePoses(poses.at(run.name), reference, names);
  }
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

}  // namespace

Comparison CompareMappers(const CompareOptions& given) {
  CheckOptions(given);
  CompareOptions options = given;
  if (options.image_path.empty()) options.image_path = options.output_path + "/no_images";
  const std::vector<std::string> names = ReadDatabaseImageNames(options.database_path);
  const std::map<std::string, Rigid3d> gt_poses = GroundTruthPoses(options, names);

  Comparison comparison;
  if (!options.peer_colmap_binary.empty()) {
    comparison.peer_version = ColmapVersion(options.peer_colmap_binary);
  }
  const std::vector<MapperPlan> plans = MapperPlans(options, comparison.peer_version);
  for (const MapperPlan& plan : plans) {
    CheckRunFolder(options.output_path, plan, options.database_path);
  }
  fs::create_directories(options.output_path);
  fs::create_directories(options.image_path);

  comparison.database_path = options.database_path;
  comparison.num_images = static_cast<int>(names.size());
  comparison.reference = gt_poses.empty() ? std::string("the COLMAP model (no ground truth given)")
                                          : "ground truth " + options.ground_truth_path + " (" +
                                                options.ground_truth_format + ")";
  std::map<std::string, Reconstruction> models;
  PosesByRun poses;
  for (const MapperPlan& plan : plans) {
    comparison.runs.push_back(RunMapperPlan(plan, options, names.size(), &models[plan.name]));
    const MapperRun& run = comparison.runs.back();
    poses[run.name] = run.succeeded ? PosesByName(models[run.name], run.model_path)
                                    : std::map<std::string, Rigid3d>();
  }

  const bool against_colmap = gt_poses.empty();
  const std::map<std::string, Rigid3d>& reference =
      against_colmap ? poses[mapper_row::kColmap] : gt_poses;
  EvaluateRuns(reference, against_colmap, poses, names, &comparison);

  // The data set's name, as the folder of its database.
  const std::string title = fs::absolute(options.database_path).parent_path().filename().string();
  if (options.png_figures) {
    DrawComparisonFigures(names, reference, against_colmap, poses, title, options.output_path,
                          &comparison);
  }
  WriteReports(comparison, options.output_path);
  // The page is for looking at the comparison; report.md and report.json are its result. A page
  // that cannot be made costs a warning.
  try {
    WriteComparisonPage(comparison, names, gt_poses, given.image_path, title, options.output_path,
                        &models);
  } catch (const std::exception& error) {
    std::cerr << "ramap compare: warning: report.html not written: " << error.what() << "\n";
  }
  ThrowIfAnyRunFailed(comparison, options.output_path);
  return comparison;
}

}  // namespace ramap
