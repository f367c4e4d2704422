// The one progress-line format every command prints the mapper's stages in, "[ramap] <stage padded
// to 22> <seconds, 3 decimals, width 8> s  <message>", and what a stage reports besides its
// result: its time, the pairs and images it left out and why. Stages write their report into the
// component's state (mapper/mapper_state.h); the summary is made from the reports at the end.
#pragma once

#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "ramap/estimators/stage_names.h"

namespace ramap {

struct MapperStageTiming {
  std::string stage;
  double seconds = 0.0;
};

// Why an image or an edge is missing from the output.
struct DroppedItem {
  std::string what;  // "IMAGE_NAME" or "NAME1 NAME2"
  std::string reason;
};

// What the stages of one pass, or of one component, reported.
struct StageReport {
  // Per stage, its seconds summed over its calls, in the order the stages first ran.
  std::vector<MapperStageTiming> timings;
  std::vector<DroppedItem> dropped_edges;
  std::vector<DroppedItem> prior_outliers;  // pose priors the prior alignment rejected
  // Why each image is not (yet) in a model; a later stage's reason replaces an earlier one's.
  std::map<uint32_t, std::string> image_reasons;
  int num_keyframes = 0;
  int num_loop_edges = 0;
};

// Adds `seconds` to `stage` in `report`, prints the stage's line to `progress` (when given) and
// tells the run's observer (util/run_observer.h).
void RecordStage(const std::string& stage, double seconds, const std::string& message,
                 std::ostream* progress, StageReport* report);

// `later`'s timings added to `report`'s (new stages after the others), its dropped items after
// `report`'s, its image reasons over `report`'s, its keyframes and loop edges counted in.
void AppendReport(const StageReport& later, StageReport* report);

// The stages whose times the comparison report draws, in the order the mapper runs them.
const std::vector<std::string>& TimedMapperStages();

// One progress line.
void PrintStageLine(std::ostream& out, const std::string& stage, double seconds,
                    const std::string& message);

// "12.3 deg" and "4.56 m", as progress lines and summaries give angles and distances.
std::string FormatDegrees(double value);
std::string FormatMetres(double value);

}  // namespace ramap
