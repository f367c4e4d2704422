// `ramap compare`'s report.html (report/html_report.h): every mapper's largest model brought
// into the reference's frame by its evaluation's alignment, switchable in one 3D view over the
// ground truth's cameras; recall curves, per-image errors and stage times as plots; the table of
// report.md; ramap's summary.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "ramap/compare/comparison.h"
#include "ramap/scene/reconstruction.h"
#include "ramap/scene/rigid3.h"

namespace ramap {

// Writes output_path/report.html for `comparison`, whose runs are evaluated already. `names` are
// the database's images, `ground_truth` their ground-truth poses (empty when the reference is
// COLMAP's model), `image_path` the images that colour the points of models without colours
// ("": none; they are coloured in place), `title` the data set's name, `models` each run's largest
// model by run name, as the runs read it (empty for a failed run).
void WriteComparisonPage(const Comparison& comparison, const std::vector<std::string>& names,
                         const std::map<std::string, Rigid3d>& ground_truth,
                         const std::string& image_path, const std::string& title,
                         const std::string& output_path,
                         std::map<std::string, Reconstruction>* models);

}  // namespace ramap
