#include "ramap/mapper/stage_log.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

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

namespace {

// Adds `seconds` to `stage`'s entry of `timings`, a new one at the end for a stage not yet there.
void AddTiming(const std::string& stage, double seconds, std::vector<MapperStageTiming>* timings) {
  auto it = std::find_if(timings->begin(), timings->end(),
                         [&](const MapperStageTiming& t) { return t.stage == stage; });
  if (it == timings->end()) {
    timings->push_back({stage, seconds});
  } else {
    it->seconds += seconds;
  }
}

}  // namespace

void RecordStage(const std::string& stage, double seconds, const std::string& message,
                 std::ostream* progress, StageReport* report) {
  AddTiming(stage, seconds, &report->timings);
  if (progress != nullptr) PrintStageLine(*progress, stage, seconds, message);
  ReportStage(stage, seconds, message);
}

void AppendReport(const StageReport& later, StageReport* report) {
  for (const MapperStageTiming& timing : later.timings)
    AddTiming(timing.stage, timing.seconds, &report->timings);
  report->dropped_edges.insert(report->dropped_edges.end(), later.dropped_edges.begin(),
                               later.dropped_edges.end());
  report->prior_outliers.insert(report->prior_outliers.end(), later.prior_outliers.begin(),
                                later.prior_outliers.end());
  for (const auto& [image_id, reason] : later.image_reasons)
    report->image_reasons[image_id] = reason;
  report->num_keyframes += later.num_keyframes;
  report->num_loop_edges += later.num_loop_edges;
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
