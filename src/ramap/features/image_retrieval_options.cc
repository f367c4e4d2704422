#include <string>
#include <utility>
#include <vector>

#include "ramap/features/image_retrieval.h"

namespace ramap {

namespace {

using Table = OptionTable<ImageRetrievalOptions>;

void Declare(Table& t) {
  t.push_back(NumberOption<ImageRetrievalOptions>(
      "Matching.retrieval_num_words", [](auto& o) -> auto& { return o.num_words; }, AtLeast(1),
      "visual words of the vocabulary trained on the images' own descriptors"));
  t.push_back(NumberOption<ImageRetrievalOptions>(
      "Matching.retrieval_max_features_per_image",
      [](auto& o) -> auto& { return o.max_features_per_image; }, AtLeast(1),
      "the largest-scale descriptors of an image that describe it for retrieval"));
  t.push_back(NumberOption<ImageRetrievalOptions>(
      "Matching.retrieval_max_training_descriptors",
      [](auto& o) -> auto& { return o.max_training_descriptors; }, AtLeast(1),
      "descriptors the vocabulary is trained on at most"));
  t.push_back(NumberOption<ImageRetrievalOptions>(
      "Matching.retrieval_num_kmeans_iterations",
      [](auto& o) -> auto& { return o.num_kmeans_iterations; }, AtLeast(0),
      "k-means iterations of the vocabulary"));
}

}  // namespace

const OptionTable<ImageRetrievalOptions>& ImageRetrievalOptionTable() {
  static const Table table = [] {
    Table t;
    Declare(t);
    return t;
  }();
  return table;
}

}  // namespace ramap
