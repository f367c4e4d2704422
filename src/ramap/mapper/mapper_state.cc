#include "ramap/mapper/mapper_state.h"

namespace ramap {

std::string PairName(const FeatureDatabase& database, uint32_t image_id1, uint32_t image_id2) {
  return database.images.at(image_id1).name + " " + database.images.at(image_id2).name;
}

void RecordStage(const PassInput& input, const std::string& stage, double seconds,
                 const std::string& message, ComponentState* state) {
  RecordStage(stage, seconds, message, input.progress, &state->report);
}

}  // namespace ramap
