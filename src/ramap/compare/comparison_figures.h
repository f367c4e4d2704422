// The figures of a comparison (PNG files in its output folder): a top-down overlay of the camera
// centres, the rotation and position error distributions, and each run's wall time by stage.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "ramap/compare/comparison.h"
#include "ramap/compare/plots.h"
#include "ramap/scene/rigid3.h"

namespace ramap {

// Each succeeded run's stages, and what they do not cover (reading the database, writing the
// model; all of COLMAP's time) as one more: the stage-time figure's and report.html's bars.
std::vector<StageBar> StageBars(const std::vector<MapperRun>& runs);

// Draws the figures into `output_path` and adds their file names to comparison->figures.
// `names` are the database's images, `reference` the poses every run was evaluated against
// (ground truth, or COLMAP's model when `against_colmap`), `poses` each run's by its name,
// `title` the data set's name.
void DrawComparisonFigures(const std::vector<std::string>& names,
                           const std::map<std::string, Rigid3d>& reference, bool against_colmap,
                           const std::map<std::string, std::map<std::string, Rigid3d>>& poses,
                           const std::string& title, const std::string& output_path,
                           Comparison* comparison);

}  // namespace ramap
