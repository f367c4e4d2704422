#include "ramap/pipeline/mapper_context.h"

namespace ramap {

std::string PairName(const FeatureDatabase& database, uint32_t image_id1, uint32_t image_id2) {
  return database.images.at(image_id1).name + " " + database.images.at(image_id2).name;
}

}  // namespace ramap
