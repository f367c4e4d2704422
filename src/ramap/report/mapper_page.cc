#include "ramap/report/mapper_page.h"

#include <algorithm>

#include "ramap/scene/image_order.h"

namespace ramap {

nlohmann::json StageBarJson(const std::string& name,
                            const std::vector<std::pair<std::string, double>>& stage_seconds) {
  nlohmann::json stages = nlohmann::json::array();
  for (const auto& [stage, seconds] : stage_seconds) stages.push_back({stage, seconds});
  return {{"name", name}, {"stages", stages}};
}

nlohmann::json ImageOrderJson(const std::vector<std::string>& names) {
  nlohmann::json order = nlohmann::json::array();
  for (const size_t k : CaptureOrder(names)) order.push_back(names[k]);
  return order;
}

nlohmann::json MapperPageData(const std::vector<Reconstruction>& models,
                              const nlohmann::json& summary,
                              const std::vector<std::pair<std::string, double>>& stage_seconds,
                              const std::string& title, const ReportSceneOptions& given) {
  ReportSceneOptions options = given;
  if (!models.empty()) options.origin = SceneMiddle(models.front());
  size_t num_points = 0;
  std::vector<std::string> names;
  for (const Reconstruction& model : models) {
    num_points += model.points3D.size();
    for (const auto& [image_id, image] : model.images) names.push_back(image.name);
  }
  nlohmann::json models_json = nlohmann::json::array();
  for (size_t k = 0; k < models.size(); ++k) {
    // The budget shared in proportion to each model's points.
    const size_t budget =
        num_points == 0 ? 0 : options.max_points * models[k].points3D.size() / num_points;
    models_json.push_back(ReportModelJson("model " + std::to_string(k), models[k], Sim3d(), nullptr,
                                          std::max<size_t>(budget, 1), options));
  }
  const int registered = summary.value("num_registered_images", 0);
  const int total = summary.value("num_images", 0);
  return {
      {"kind", "mapper"},
      {"title", title},
      {"subtitle", "ramap mapper: " + std::to_string(registered) + " of " + std::to_string(total) +
                       " images registered in " + std::to_string(models.size()) + " model(s)"},
      {"models", models_json},
      {"reference", nullptr},
      {"origin",
       nlohmann::json::array({options.origin.x(), options.origin.y(), options.origin.z()})},
      {"image_order", ImageOrderJson(names)},
      {"stage_seconds", nlohmann::json::array({StageBarJson("ramap mapper", stage_seconds)})},
      {"summary", summary},
      {"summary_title", "The mapper's summary"}};
}

}  // namespace ramap
