#include "ramap/features/image_retrieval.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <numeric>
#include <optional>
#include <set>

#include "ramap/features/descriptor_matching.h"
#include "ramap/util/blas_threads.h"
#include "ramap/util/cblas.h"
#include "ramap/util/error.h"
#include "ramap/util/option_check.h"
#include "ramap/util/parallel.h"

namespace ramap {
namespace {

int FloatDimension(int num_cols) { return num_cols == 32 ? 256 : num_cols; }

// Descriptors as floats in the space the vocabulary lives in. SIFT as RootSIFT (Arandjelovic,
// Zisserman, "Three things everyone should know to improve object retrieval", CVPR 2012): L1
// normalised and square-rooted, so that Euclidean distance compares histograms by the Hellinger
// kernel. Binary descriptors as one 0/1 column per bit, so that squared distance is Hamming's.
std::vector<float> RetrievalFloats(const Descriptors& descriptors) {
  const size_t n = descriptors.size();
  const int cols = descriptors.num_cols, dim = FloatDimension(cols);
  std::vector<float> rows(n * dim);
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* in = &descriptors.data[i * cols];
    float* out = &rows[i * dim];
    if (cols == 32) {
      for (int bit = 0; bit < 256; ++bit) out[bit] = (in[bit / 8] >> (bit % 8)) & 1;
      continue;
    }
    const float sum = std::accumulate(in, in + cols, 0.0f);
    for (int c = 0; c < cols; ++c) out[c] = sum > 0 ? std::sqrt(in[c] / sum) : 0.0f;
  }
  return rows;
}

// The nearest word of every row, by one matrix product (|x - w|^2 = |w|^2 - 2 x.w + const).
std::vector<int> NearestWords(const std::vector<float>& rows, const std::vector<float>& words,
                              int dim) {
  const int n = static_cast<int>(rows.size() / dim), k = static_cast<int>(words.size() / dim);
  std::vector<int> nearest(n, 0);
  if (n == 0) return nearest;
  std::vector<float> word_norms(k, 0.0f);
  for (int w = 0; w < k; ++w) {
    for (int c = 0; c < dim; ++c) word_norms[w] += words[w * dim + c] * words[w * dim + c];
  }
  std::vector<float> products(static_cast<size_t>(n) * k);
  cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasTrans, n, k, dim, 1.0f, rows.data(), dim,
              words.data(), dim, 0.0f, products.data(), k);
  for (int i = 0; i < n; ++i) {
    float best = FLT_MAX;
    for (int w = 0; w < k; ++w) {
      const float d = word_norms[w] - 2.0f * products[static_cast<size_t>(i) * k + w];
      if (d < best) best = d, nearest[i] = w;
    }
  }
  return nearest;
}

// Lloyd's k-means from evenly spaced samples (deterministic); a word that loses all its samples
// keeps its place.
std::vector<float> TrainVocabulary(const std::vector<float>& samples, int dim,
                                   const ImageRetrievalOptions& options) {
  const size_t n = samples.size() / dim;
  const int k = static_cast<int>(std::min<size_t>(options.num_words, n));
  std::vector<float> words(static_cast<size_t>(k) * dim);
  for (int w = 0; w < k; ++w) {
    std::copy_n(&samples[(w * n / k) * dim], dim, &words[static_cast<size_t>(w) * dim]);
  }
  for (int iteration = 0; iteration < options.num_kmeans_iterations; ++iteration) {
    const std::vector<int> nearest = NearestWords(samples, words, dim);
    std::vector<double> sums(words.size(), 0.0);
    std::vector<int> counts(k, 0);
    for (size_t i = 0; i < n; ++i) {
      ++counts[nearest[i]];
      for (int c = 0; c < dim; ++c) sums[nearest[i] * dim + c] += samples[i * dim + c];
    }
    for (int w = 0; w < k; ++w) {
      if (counts[w] == 0) continue;
      for (int c = 0; c < dim; ++c) words[w * dim + c] = sums[w * dim + c] / counts[w];
    }
  }
  return words;
}

void Normalize(float* values, size_t count) {
  double norm = 0;
  for (size_t c = 0; c < count; ++c) norm += double{values[c]} * values[c];
  if (norm <= 0) return;
  const float scale = static_cast<float>(1.0 / std::sqrt(norm));
  for (size_t c = 0; c < count; ++c) values[c] *= scale;
}

// Residuals to the nearest word summed per word, each word's sum normalised, then the whole.
void Vlad(const std::vector<float>& rows, const std::vector<float>& words, int dim, float* out) {
  const size_t num_words = words.size() / dim;
  std::fill(out, out + num_words * dim, 0.0f);
  const std::vector<int> nearest = NearestWords(rows, words, dim);
  for (size_t i = 0; i < nearest.size(); ++i) {
    float* sum = out + static_cast<size_t>(nearest[i]) * dim;
    const float* word = &words[static_cast<size_t>(nearest[i]) * dim];
    for (int c = 0; c < dim; ++c) sum[c] += rows[i * dim + c] - word[c];
  }
  for (size_t w = 0; w < num_words; ++w) Normalize(out + w * dim, dim);
  Normalize(out, num_words * dim);
}

const Descriptors& DescriptorsOf(const FeatureDatabase& database, uint32_t image_id) {
  const auto found = database.descriptors.find(image_id);
  if (found == database.descriptors.end() || !database.keypoints.count(image_id)) {
    const auto image = database.images.find(image_id);
    throw InputError(
        database.source_path.empty() ? "database" : database.source_path,
        "image " +
            (image == database.images.end() ? std::to_string(image_id) : image->second.name) +
            " has no keypoints or descriptors for image retrieval");
  }
  return found->second;
}

Descriptors VotingDescriptors(const FeatureDatabase& database, uint32_t image_id,
                              const ImageRetrievalOptions& options) {
  return LargestScaleDescriptors(database.keypoints.at(image_id), DescriptorsOf(database, image_id),
                                 options.max_features_per_image);
}

}  // namespace

void ImageRetrievalOptions::Check() const { CheckOptionValues(ImageRetrievalOptionTable(), *this); }

GlobalDescriptors ComputeGlobalDescriptors(const FeatureDatabase& database,
                                           const std::vector<uint32_t>& image_ids,
                                           const ImageRetrievalOptions& options, int num_threads) {
  options.Check();
  GlobalDescriptors global;
  global.image_ids = image_ids;
  if (image_ids.empty()) return global;
  const int cols = DescriptorsOf(database, image_ids.front()).num_cols;
  for (const uint32_t id : image_ids) {
    if (DescriptorsOf(database, id).num_cols != cols) {
      throw InputError(database.source_path.empty() ? "database" : database.source_path,
                       "images with descriptors of different lengths cannot be compared");
    }
  }
  const int dim = FloatDimension(cols);
  // Training samples evenly drawn from every image's voting descriptors; only those are converted
  // (the voting descriptors are selected again for the VLAD pass below rather than kept: as floats
  // they would take gigabytes on collections of thousands of images).
  const size_t per_image = std::max<size_t>(1, options.max_training_descriptors / image_ids.size());
  std::vector<float> samples;
  for (const uint32_t id : image_ids) {
    const Descriptors voting = VotingDescriptors(database, id, options);
    const size_t n = voting.size(), take = std::min(n, per_image);
    Descriptors drawn;
    drawn.num_cols = voting.num_cols;
    for (size_t k = 0; k < take; ++k) {
      const auto row = voting.data.begin() + (k * n / take) * voting.num_cols;
      drawn.data.insert(drawn.data.end(), row, row + voting.num_cols);
    }
    const std::vector<float> rows = RetrievalFloats(drawn);
    samples.insert(samples.end(), rows.begin(), rows.end());
  }
  if (samples.empty()) return global;
  const std::vector<float> words = TrainVocabulary(samples, dim, options);
  global.dimension = static_cast<int>(words.size());
  global.rows.assign(image_ids.size() * global.dimension, 0.0f);
  std::optional<SingleBlasThread> single_blas_thread;
  if (num_threads > 1) single_blas_thread.emplace();
  ParallelFor(image_ids.size(), num_threads, [&](size_t k) {
    Vlad(RetrievalFloats(VotingDescriptors(database, image_ids[k], options)), words, dim,
         &global.rows[k * global.dimension]);
  });
  return global;
}

std::vector<std::pair<uint32_t, uint32_t>> MostSimilarPairs(const GlobalDescriptors& descriptors,
                                                            int num_neighbors, int min_index_gap) {
  const int n = static_cast<int>(descriptors.image_ids.size());
  const int dim = descriptors.dimension;
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  if (n < 2 || num_neighbors <= 0 || dim == 0) return pairs;
  std::set<std::pair<uint32_t, uint32_t>> seen;
  constexpr int kBlockRows = 256;
  std::vector<float> similarities(static_cast<size_t>(std::min(n, kBlockRows)) * n);
  std::vector<int> candidates;
  for (int begin = 0; begin < n; begin += kBlockRows) {
    const int rows = std::min(kBlockRows, n - begin);
    cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasTrans, rows, n, dim, 1.0f, descriptors.row(begin),
                dim, descriptors.rows.data(), dim, 0.0f, similarities.data(), n);
    for (int r = 0; r < rows; ++r) {
      const int i = begin + r;
      const float* row = &similarities[static_cast<size_t>(r) * n];
      candidates.clear();
      for (int j = 0; j < n; ++j) {
        if (std::abs(i - j) > min_index_gap && j != i) candidates.push_back(j);
      }
      const size_t keep = std::min<size_t>(num_neighbors, candidates.size());
      // Most similar first; ties to the lower index, so the plan does not depend on the sort.
      std::partial_sort(candidates.begin(), candidates.begin() + keep, candidates.end(),
                        [&](int a, int b) { return row[a] != row[b] ? row[a] > row[b] : a < b; });
      for (size_t c = 0; c < keep; ++c) {
        const uint32_t a = descriptors.image_ids[i], b = descriptors.image_ids[candidates[c]];
        const std::pair<uint32_t, uint32_t> pair(std::min(a, b), std::max(a, b));
        if (seen.insert(pair).second) pairs.push_back(pair);
      }
    }
  }
  return pairs;
}

}  // namespace ramap
