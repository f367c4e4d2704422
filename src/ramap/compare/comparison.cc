#include "ramap/compare/comparison.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace ramap {
namespace {

// The run named `name`, or nullptr.
const MapperRun* RunNamed(const Comparison& comparison, const std::string& name) {
  for (const MapperRun& run : comparison.runs) {
    if (run.name == name) return &run;
  }
  return nullptr;
}

// `baseline`'s seconds over the run's, or NaN when either is missing or failed.
double SpeedRatio(const MapperRun* baseline, const MapperRun& run) {
  if (baseline == nullptr || !baseline->succeeded || !run.succeeded || !(run.seconds > 0)) {
    return std::nan("");
  }
  return baseline->seconds / run.seconds;
}

// COLMAP's seconds over the run's (COLMAP's is the first run).
double SpeedRatio(const Comparison& comparison, const MapperRun& run) {
  return SpeedRatio(comparison.runs.empty() ? nullptr : &comparison.runs[0], run);
}

const MapperRun* GlomapRun(const Comparison& comparison) {
  return RunNamed(comparison, mapper_row::kGlomap);
}

nlohmann::json OptionalNumber(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json();
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
                         {"peer_version", comparison.peer_version},
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
    entry["speedup_over_colmap"] = OptionalNumber(SpeedRatio(comparison, run));
    if (GlomapRun(comparison) != nullptr) {
      entry["speedup_over_glomap"] = OptionalNumber(SpeedRatio(GlomapRun(comparison), run));
    }
    for (const auto& [stage, seconds] : run.stage_seconds) entry["stage_seconds"][stage] = seconds;
    entry["evaluation"] =
        run.evaluation ? PoseEvaluationToJson(*run.evaluation, false) : nlohmann::json();
    json["runs"].push_back(entry);
  }
  return json;
}

namespace {

std::string RatioCell(double ratio) {
  return std::isfinite(ratio) ? Fixed(ratio, 1) + "x" : std::string("-");
}

// AUC@3 in %, "-" without an evaluation (auc holds the thresholds 1, 3, 5, 10 degrees).
std::string Auc3(const MapperRun& run) {
  return run.evaluation && run.evaluation->auc.size() > 1 ? Fixed(100 * run.evaluation->auc[1], 1)
                                                          : std::string("-");
}

void WriteTableRow(const Comparison& comparison, const MapperRun& run, std::ostream& out) {
  out << "| " << run.name << " | "
      << (run.succeeded ? std::to_string(run.num_registered) : std::string("failed")) << " / "
      << comparison.num_images;
  if (run.evaluation) {
    const PoseEvaluation& e = *run.evaluation;
    for (size_t k = 0; k < e.auc.size() && k < 3; ++k) out << " | " << Fixed(100 * e.auc[k], 1);
    out << " | " << Fixed(e.rotation_error_median_deg, 3) << " | "
        << Fixed(e.relative_rotation_error_median_deg, 3) << " | " << Fixed(e.ate_rmse, 4) << " | "
        << Fixed(100 * e.ate_rmse_over_extent, 2) << "%";
  } else {
    out << " | | | | | (reference) | | ";
  }
  out << " | " << Fixed(run.seconds, 2) << " | " << RatioCell(SpeedRatio(comparison, run));
  if (GlomapRun(comparison) != nullptr) {
    out << " | " << RatioCell(SpeedRatio(GlomapRun(comparison), run));
  }
  out << " |\n";
}

// "Against GLOMAP (AUC@3 a, t s): ramap+BA r.rx as fast at AUC@3 b; ..." for the runs after it
// (ramap's); "-" for a ratio or an AUC that cannot be given.
void WriteGlomapRatios(const Comparison& comparison, std::ostream& out) {
  const MapperRun* glomap = GlomapRun(comparison);
  if (glomap == nullptr) return;
  if (!glomap->succeeded) {
    out << "\nGLOMAP failed: no ratios against it.\n";
    return;
  }
  out << "\nAgainst GLOMAP (AUC@3 " << Auc3(*glomap) << ", " << Fixed(glomap->seconds, 2) << " s):";
  const char* separator = " ";
  for (auto run = comparison.runs.begin() + (glomap - comparison.runs.data()) + 1;
       run != comparison.runs.end(); ++run) {
    out << separator << run->name << " " << RatioCell(SpeedRatio(glomap, *run))
        << " as fast at AUC@3 " << Auc3(*run);
    separator = "; ";
  }
  out << ".\n";
}

}  // namespace

std::string ComparisonToMarkdown(const Comparison& comparison) {
  const bool with_glomap = GlomapRun(comparison) != nullptr;
  std::ostringstream out;
  out << "# ramap compare\n\n"
      << "Database: `" << comparison.database_path << "` (" << comparison.num_images
      << " images). Reference: " << comparison.reference << ".\n\n"
      << "| mapper | registered | AUC@1 | AUC@3 | AUC@5 | rot. err. median (deg) | rel. rot. err. "
         "median (deg) | ATE RMSE | ATE / extent | seconds | speed-up over COLMAP |"
      << (with_glomap ? " speed-up over GLOMAP |" : "") << "\n"
      << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
      << (with_glomap ? " --- |" : "") << "\n";
  for (const MapperRun& run : comparison.runs) WriteTableRow(comparison, run, out);
  WriteGlomapRatios(comparison, out);
  out << "\nAUC in %, over every image pair (an unregistered image makes its pairs failures); "
         "rotation error after the Sim(3) alignment of the camera centres; relative rotation "
         "error over the pairs of registered images (free of any alignment).\n\n## Commands\n\n";
  for (const MapperRun& run : comparison.runs) {
    out << "- " << run.name << ": `" << run.command << "`\n";
  }
  out << "\nreport.html beside this file shows the models in 3D, the recall curves, the per-image "
         "errors and the stage times.\n";
  if (!comparison.figures.empty()) out << "\n## Figures\n\n";
  for (const std::string& figure : comparison.figures) {
    out << "![" << figure << "](" << figure << ")\n\n";
  }
  return out.str();
}

}  // namespace ramap
