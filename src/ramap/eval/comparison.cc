#include "ramap/eval/comparison.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace ramap {
namespace {

// COLMAP's seconds over the run's, or NaN when either is missing.
double SpeedRatio(const Comparison& comparison, const MapperRun& run) {
  if (comparison.runs.empty() || !comparison.runs[0].succeeded || !run.succeeded ||
      !(run.seconds > 0)) {
    return std::nan("");
  }
  return comparison.runs[0].seconds / run.seconds;
}

std::string Fixed(double value, int digits) {
  if (!std::isfinite(value)) return "-";
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << value;
  return out.str();
}

}  // namespace

nlohmann::json ComparisonToJson(const Comparison& comparison) {
  nlohmann::json json = {{"database_path", comparison.database_path},
                         {"reference", comparison.reference},
                         {"num_images", comparison.num_images},
                         {"figures", comparison.figures}};
  json["runs"] = nlohmann::json::array();
  for (const MapperRun& run : comparison.runs) {
    nlohmann::json entry = {{"name", run.name},
                            {"command", run.command},
                            {"model_path", run.model_path},
                            {"succeeded", run.succeeded},
                            {"seconds", run.seconds},
                            {"num_models", run.num_models},
                            {"num_registered", run.num_registered}};
    for (const auto& [camera_id, focal] : run.focal_lengths_px) {
      entry["focal_lengths_px"][std::to_string(camera_id)] = focal;
    }
    const double ratio = SpeedRatio(comparison, run);
    entry["speedup_over_colmap"] = std::isfinite(ratio) ? nlohmann::json(ratio) : nlohmann::json();
    for (const auto& [stage, seconds] : run.stage_seconds) entry["stage_seconds"][stage] = seconds;
    entry["evaluation"] =
        run.evaluation ? PoseEvaluationToJson(*run.evaluation, false) : nlohmann::json();
    json["runs"].push_back(entry);
  }
  return json;
}

std::string ComparisonToMarkdown(const Comparison& comparison) {
  std::ostringstream out;
  out << "# ramap compare\n\n"
      << "Database: `" << comparison.database_path << "` (" << comparison.num_images
      << " images). Reference: " << comparison.reference << ".\n\n"
      << "| mapper | registered | AUC@1 | AUC@3 | AUC@5 | rot. err. median (deg) | rel. rot. err. "
         "median (deg) | ATE RMSE | ATE / extent | seconds | speed-up over COLMAP |\n"
      << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const MapperRun& run : comparison.runs) {
    out << "| " << run.name << " | "
        << (run.succeeded ? std::to_string(run.num_registered) : std::string("failed")) << " / "
        << comparison.num_images;
    if (run.evaluation) {
      const PoseEvaluation& e = *run.evaluation;
      for (size_t k = 0; k < e.auc.size() && k < 3; ++k) out << " | " << Fixed(100 * e.auc[k], 1);
      out << " | " << Fixed(e.rotation_error_median_deg, 3) << " | "
          << Fixed(e.relative_rotation_error_median_deg, 3) << " | " << Fixed(e.ate_rmse, 4)
          << " | " << Fixed(100 * e.ate_rmse_over_extent, 2) << "%";
    } else {
      out << " | | | | | (reference) | | ";
    }
    const double ratio = SpeedRatio(comparison, run);
    out << " | " << Fixed(run.seconds, 2) << " | "
        << (std::isfinite(ratio) ? Fixed(ratio, 1) + "x" : std::string("-")) << " |\n";
  }
  out << "\nAUC in %, over every image pair (an unregistered image makes its pairs failures); "
         "rotation error after the Sim(3) alignment of the camera centres; relative rotation "
         "error over the pairs of registered images (free of any alignment).\n\n## Commands\n\n";
  for (const MapperRun& run : comparison.runs) {
    out << "- " << run.name << ": `" << run.command << "`\n";
  }
  if (!comparison.figures.empty()) out << "\n## Figures\n\n";
  for (const std::string& figure : comparison.figures) {
    out << "![" << figure << "](" << figure << ")\n\n";
  }
  return out.str();
}

}  // namespace ramap
