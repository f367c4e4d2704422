// report.html: one self-contained page (its style, script and the pinned three.js inlined, no
// network, opens from file://) that shows what report_scene.h and the caller put in its data: the
// models in 3D, plots as SVG, the tables and the mapper's summary. The page's code lives in
// report/assets and is compiled in.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace ramap {

// The page for `data`: {"kind": "mapper"|"compare", "title", "subtitle", "models": [...] and
// "reference": {...}|null (report_scene.h), "origin" (what the coordinates are relative to),
// "image_order" (names in capture order: the per-image plots' x axis), "position_unit",
// "recall_curves": [...], "stage_seconds": [{"name", "stages": [[stage, seconds], ...]}],
// "comparison": report.json|null, "summary": summary.json|null, "summary_title"}; the page adds
// who wrote it (version, commit) and when.
std::string RenderHtmlReport(const nlohmann::json& data);

// Writes RenderHtmlReport(data) to `path` atomically; InputError naming the path when it cannot.
void WriteHtmlReport(const nlohmann::json& data, const std::string& path);

}  // namespace ramap
