#include "ramap/pipeline/stage_log.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include "ramap/pipeline/mapper_summary.h"
#include "ramap/util/run_observer.h"

namespace ramap {

const std::vector<std::string>& TimedMapperStages() {
  static const std::vector<std::string> stages = {
      stage::kBearings,          stage::kRelativePoses,
      stage::kRotationAveraging, stage::kTranslationAveraging,
      stage::kTriangulation,     stage::kBundleAdjustment};
  return stages;
}

void PrintStageLine(std::ostream& out, const std::string& stage, double seconds,
                    const std::string& message) {
  out << "[ramap] " << std::left << std::setw(22) << stage << std::right << std::fixed
      << std::setprecision(3) << std::setw(8) << seconds << " s  " << message << "\n"
      << std::flush;
}

void StageLog::Record(const std::string& stage, double seconds, const std::string& message) {
  auto it = std::find_if(summary_->timings.begin(), summary_->timings.end(),
                         [&](const MapperStageTiming& t) { return t.stage == stage; });
  if (it == summary_->timings.end()) {
    summary_->timings.push_back({stage, seconds});
  } else {
    it->seconds += seconds;
  }
  if (progress_ != nullptr) PrintStageLine(*progress_, stage, seconds, message);
  ReportStage(stage, seconds, message);
}

std::string FormatDegrees(double value) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(1) << value << " deg";
  return out.str();
}

std::string FormatMetres(double value) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(2) << value << " m";
  return out.str();
}

}  // namespace ramap
