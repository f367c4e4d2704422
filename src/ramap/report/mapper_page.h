// The data of `ramap mapper`'s report.html (html_report.h): its models, each in its own frame
// (there is no reference), the cameras coloured by their mean reprojection error, the stage times
// and the whole summary.json.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "ramap/report/report_scene.h"
#include "ramap/scene/reconstruction.h"

namespace ramap {

nlohmann::json MapperPageData(const std::vector<Reconstruction>& models,
                              const nlohmann::json& summary,
                              const std::vector<std::pair<std::string, double>>& stage_seconds,
                              const std::string& title,
                              const ReportSceneOptions& options = ReportSceneOptions());

// The page's stage bar: one row of the stages in the order they ran.
nlohmann::json StageBarJson(const std::string& name,
                            const std::vector<std::pair<std::string, double>>& stage_seconds);

// The registered images' names of every model, in capture order: the x axis of per-image plots.
nlohmann::json ImageOrderJson(const std::vector<std::string>& names);

}  // namespace ramap
