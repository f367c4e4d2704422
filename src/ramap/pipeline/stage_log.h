// The mapper's stages by name, and the one progress-line format every command prints them in:
// "[ramap] <stage padded to 22> <seconds, 3 decimals, width 8> s  <message>".
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace ramap {

struct MapperSummary;

// Stage names, as summary.json's stage_seconds keys them.
namespace stage {
inline const std::string kViewGraphCalibration = "view-graph calibration";
inline const std::string kBearings = "bearings";
inline const std::string kRelativePoses = "relative poses";
inline const std::string kRotationAveraging = "rotation averaging";
inline const std::string kTranslationAveraging = "translation averaging";
inline const std::string kPriorAlignment = "prior alignment";
inline const std::string kTriangulation = "triangulation";
inline const std::string kBundleAdjustment = "bundle adjustment";
}  // namespace stage

// The stages whose times the comparison report draws, in the order the mapper runs them.
const std::vector<std::string>& TimedMapperStages();

// One progress line.
void PrintStageLine(std::ostream& out, const std::string& stage, double seconds,
                    const std::string& message);

// "12.3 deg" and "4.56 m", as progress lines and summaries give angles and distances.
std::string FormatDegrees(double value);
std::string FormatMetres(double value);

// Accumulates stage times in `summary->timings` (a stage may run once per component) and prints
// one line per call to `progress`, when given.
class StageLog {
 public:
  StageLog(MapperSummary* summary, std::ostream* progress)
      : summary_(summary), progress_(progress) {}

  void Record(const std::string& stage, double seconds, const std::string& message);
  // Where stages draw their progress lines (util/progress_line.h); nullptr: nowhere.
  std::ostream* progress() const { return progress_; }

 private:
  MapperSummary* summary_;
  std::ostream* progress_;
};

}  // namespace ramap
