#include "ramap/compare/comparison_page.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "ramap/compare/comparison_figures.h"
#include "ramap/io/point_colors.h"
#include "ramap/report/html_report.h"
#include "ramap/report/mapper_page.h"
#include "ramap/report/report_scene.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

struct PageModel {
  const MapperRun* run;
  const Reconstruction* model;
};

bool HasColors(const Reconstruction& model) {
  return std::any_of(model.points3D.begin(), model.points3D.end(), [](const auto& entry) {
    return entry.second.color != Eigen::Matrix<uint8_t, 3, 1>::Zero();
  });
}

// The largest model of each succeeded run. Points the run left without colours (ramap's runs are
// timed without reading the images) take them from `image_path` here, outside every timing, when
// it is given.
std::vector<PageModel> RunModels(const Comparison& comparison, const std::string& image_path,
                                 std::map<std::string, Reconstruction>* models) {
  std::vector<PageModel> page_models;
  for (const MapperRun& run : comparison.runs) {
    const auto model = models->find(run.name);
    if (!run.succeeded || model == models->end()) continue;
    if (!image_path.empty() && !HasColors(model->second)) {
      ColorPointsFromImages(image_path, &model->second);
    }
    page_models.push_back({&run, &model->second});
  }
  return page_models;
}

// summary.json of the last ramap run (with BA when there is one), or null.
nlohmann::json RamapSummary(const Comparison& comparison, std::string* whose) {
  for (auto run = comparison.runs.rbegin(); run != comparison.runs.rend(); ++run) {
    if (!run->succeeded || run->model_path.empty()) continue;
    const fs::path path = fs::path(run->model_path).parent_path() / "summary.json";
    std::ifstream in(path);
    if (!in) continue;
    nlohmann::json summary = nlohmann::json::parse(in, nullptr, false);
    if (summary.is_discarded()) continue;
    *whose = run->name;
    return summary;
  }
  return nullptr;
}

}  // namespace

void WriteComparisonPage(const Comparison& comparison, const std::vector<std::string>& names,
                         const std::map<std::string, Rigid3d>& ground_truth,
                         const std::string& image_path, const std::string& title,
                         const std::string& output_path,
                         std::map<std::string, Reconstruction>* run_models) {
  const std::vector<PageModel> models = RunModels(comparison, image_path, run_models);
  ReportSceneOptions options;
  // The page's origin: the middle of the reference's cameras (the ground truth's, else the
  // first model's, COLMAP's, which is the reference then).
  if (!ground_truth.empty()) {
    options.origin = SceneMiddle(ModelOfPoses(ground_truth, Camera()));
  } else if (!models.empty()) {
    const MapperRun& first = *models.front().run;
    options.origin = SceneMiddle(*models.front().model,
                                 first.evaluation ? first.evaluation->gt_from_estimate : Sim3d());
  }
  size_t num_points = 0;
  for (const PageModel& page_model : models) num_points += page_model.model->points3D.size();

  nlohmann::json models_json = nlohmann::json::array();
  nlohmann::json recall_curves = nlohmann::json::array();
  for (const PageModel& page_model : models) {
    const MapperRun& run = *page_model.run;
    const PoseEvaluation* evaluation = run.evaluation ? &*run.evaluation : nullptr;
    const Sim3d reference_from_model = evaluation ? evaluation->gt_from_estimate : Sim3d();
    const size_t budget =
        num_points == 0 ? 0 : options.max_points * page_model.model->points3D.size() / num_points;
    models_json.push_back(ReportModelJson(run.name, *page_model.model, reference_from_model,
                                          evaluation, budget, options));
    if (evaluation) recall_curves.push_back(ReportRecallCurveJson(run.name, *evaluation));
  }
  nlohmann::json reference = nullptr;
  if (!ground_truth.empty()) {
    reference = ReportReferenceJson("ground truth", ground_truth,
                                    models.empty() ? nullptr : models.front().model, options);
  }
  nlohmann::json stage_bars = nlohmann::json::array();
  for (const StageBar& bar : StageBars(comparison.runs)) {
    stage_bars.push_back(StageBarJson(bar.label, bar.stages));
  }
  std::string summary_of;
  const nlohmann::json summary = RamapSummary(comparison, &summary_of);
  std::string subtitle = "ramap compare: " + std::to_string(comparison.runs.size()) +
                         " mappers on " + comparison.database_path + " (" +
                         std::to_string(comparison.num_images) +
                         " images); reference: " + comparison.reference;
  const nlohmann::json data = {
      {"kind", "compare"},
      {"title", title},
      {"subtitle", subtitle},
      {"models", models_json},
      {"reference", reference},
      {"origin",
       nlohmann::json::array({options.origin.x(), options.origin.y(), options.origin.z()})},
      {"position_unit", ground_truth.empty() ? "COLMAP model units" : "ground-truth units"},
      {"image_order", ImageOrderJson(names)},
      {"recall_curves", recall_curves},
      {"stage_seconds", stage_bars},
      {"comparison", ComparisonToJson(comparison)},
      {"summary", summary},
      {"summary_title", summary_of + "'s summary"}};
  WriteHtmlReport(data, output_path + "/report.html");
}

}  // namespace ramap
