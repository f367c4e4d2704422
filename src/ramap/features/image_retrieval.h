// Image retrieval from an image's own local features: which images of a collection look alike,
// so that matching can try those pairs and not all of them. Each image becomes one global
// descriptor, VLAD (Jegou, Douze, Schmid, Perez, "Aggregating local descriptors into a compact
// image representation", CVPR 2010) with intra-normalisation (Arandjelovic, Zisserman, "All about
// VLAD", CVPR 2013), over a vocabulary trained by k-means on the collection's own descriptors:
// nothing is downloaded, and it works for SIFT and ORB alike.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "ramap/scene/features.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct ImageRetrievalOptions {
  // Visual words of the vocabulary. 64 words of 128 (SIFT) or 256 (ORB, one column per bit)
  // dimensions make an 8192- or 16384-float descriptor per image.
  int num_words = 64;
  // Descriptors of an image that vote: its largest-scale ones (the most repeatable).
  int max_features_per_image = 1000;
  // Descriptors the vocabulary is trained on, evenly drawn from all images, and k-means rounds.
  int max_training_descriptors = 100000;
  int num_kmeans_iterations = 10;

  void Check() const;  // throws InputError naming the option
};

// Its options (--Matching.*), each declared once with its range and help (util/option_table.h):
// the command line, Check(), summary.json and Python read them.
const OptionTable<ImageRetrievalOptions>& ImageRetrievalOptionTable();

// One row per image, in the order of `image_ids`: unit-length VLAD descriptors, so that a dot
// product is the cosine similarity of two images.
struct GlobalDescriptors {
  std::vector<uint32_t> image_ids;
  int dimension = 0;
  std::vector<float> rows;  // image_ids.size() x dimension, row-major

  const float* row(size_t k) const { return &rows[k * dimension]; }
};

// The global descriptor of every image in `image_ids` (each must have keypoints and descriptors
// in `database`) over a vocabulary trained on those images, on `num_threads` threads.
GlobalDescriptors ComputeGlobalDescriptors(const FeatureDatabase& database,
                                           const std::vector<uint32_t>& image_ids,
                                           const ImageRetrievalOptions& options, int num_threads);

// For every image, the `num_neighbors` most similar others whose positions in image_ids differ by
// more than `min_index_gap` (0: any other image), as image id pairs (smaller id first), each pair
// once, in order of first appearance.
std::vector<std::pair<uint32_t, uint32_t>> MostSimilarPairs(const GlobalDescriptors& descriptors,
                                                            int num_neighbors,
                                                            int min_index_gap = 0);

}  // namespace ramap
