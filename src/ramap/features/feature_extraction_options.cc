#include <string>
#include <utility>
#include <vector>

#include "ramap/features/feature_extraction.h"

namespace ramap {

namespace {

using Table = OptionTable<FeatureExtractionOptions>;

void Declare(Table& t) {
  t.push_back(ChoiceOption<FeatureExtractionOptions>(
      "FeatureExtraction.type", [](auto& o) -> auto& { return o.type; },
      std::vector<std::pair<std::string, FeatureType>>{{"sift", FeatureType::kSift},
                                                       {"orb", FeatureType::kOrb}},
      "OpenCV's SIFT or ORB"));
  t.push_back(ColmapNamed(
      NumberOption<FeatureExtractionOptions>(
          "FeatureExtraction.max_image_size", [](auto& o) -> auto& { return o.max_image_size; },
          AtLeast(32), "images are scaled down to this longest side first"),
      {"SiftExtraction.max_image_size"}));
  t.push_back(ColmapNamed(
      NumberOption<FeatureExtractionOptions>(
          "FeatureExtraction.max_num_features", [](auto& o) -> auto& { return o.max_num_features; },
          AtLeast(16), "features per image at most"),
      {"SiftExtraction.max_num_features"}));
}

}  // namespace

const OptionTable<FeatureExtractionOptions>& FeatureExtractionOptionTable() {
  static const Table table = [] {
    Table t;
    Declare(t);
    // COLMAP's options of this step that have no meaning here.
    t.push_back(IgnoredColmapOption<FeatureExtractionOptions>("SiftExtraction.use_gpu",
                                                              "ramap runs on the CPU"));
    t.push_back(IgnoredColmapOption<FeatureExtractionOptions>("SiftExtraction.gpu_index",
                                                              "ramap runs on the CPU"));
    t.push_back(IgnoredColmapOption<FeatureExtractionOptions>("FeatureExtraction.use_gpu",
                                                              "ramap runs on the CPU"));
    t.push_back(IgnoredColmapOption<FeatureExtractionOptions>("FeatureExtraction.gpu_index",
                                                              "ramap runs on the CPU"));
    return t;
  }();
  return table;
}

}  // namespace ramap
