// The names of the mapper's stages, as its progress lines, summary.json's stage times and the
// comparison report give them; an estimator that draws a progress line names its stage so.
#pragma once

#include <string>

namespace ramap::stage {

inline const std::string kViewGraphCalibration = "view-graph calibration";
inline const std::string kBearings = "bearings";
inline const std::string kRelativePoses = "relative poses";
inline const std::string kRotationAveraging = "rotation averaging";
inline const std::string kTranslationAveraging = "translation averaging";
inline const std::string kPriorAlignment = "prior alignment";
inline const std::string kTriangulation = "triangulation";
inline const std::string kBundleAdjustment = "bundle adjustment";

}  // namespace ramap::stage
