#include "ramap/synthetic/synthetic_descriptors.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "ramap/util/option_check.h"

namespace ramap {
namespace {

constexpr int kDimension = 128;

// A SIFT-shaped vector: non-negative, L2 norm 512, no value above 255.
std::vector<float> SiftShaped(std::vector<float> values) {
  double norm = 0;
  for (float& v : values) v = std::max(0.0f, v), norm += double{v} * v;
  const float scale = norm > 0 ? static_cast<float>(512.0 / std::sqrt(norm)) : 0.0f;
  for (float& v : values) v = std::min(255.0f, v * scale);
  return values;
}

std::vector<float> RandomDescriptor(std::mt19937_64& rng) {
  std::normal_distribution<float> normal(0.0f, 1.0f);
  std::vector<float> values(kDimension);
  for (float& v : values) v = std::abs(normal(rng));
  return SiftShaped(std::move(values));
}

void AppendBytes(const std::vector<float>& values, std::vector<uint8_t>* out) {
  for (const float v : values) out->push_back(static_cast<uint8_t>(v + 0.5f));  // v in [0, 255]
}

// Adds uniform noise of standard deviation `sigma` to every value, four 8-bit draws per call of
// the generator: Gaussian draws per value made a 5000-image collection's descriptors take minutes.
void AddNoise(double sigma, std::mt19937_64& rng, std::vector<float>* values) {
  const float scale = static_cast<float>(sigma * std::sqrt(12.0) / 256.0);
  uint64_t bits = 0;
  for (size_t k = 0; k < values->size(); ++k) {
    if (k % 8 == 0) bits = rng();
    (*values)[k] += scale * (static_cast<float>(bits & 0xff) - 127.5f);
    bits >>= 8;
  }
}

}  // namespace

void SyntheticDescriptorOptions::Check() const {
  CheckOptionValues(SyntheticDescriptorOptionTable(), *this);
}

void AddSyntheticDescriptors(const SyntheticDescriptorOptions& options, SyntheticScene* scene) {
  options.Check();
  std::mt19937_64 rng(options.seed ^ 0xde5c417705ull);
  std::map<uint64_t, std::vector<float>> point_descriptors;
  for (const auto& [point3D_id, point3D] : scene->ground_truth.points3D) {
    point_descriptors[point3D_id] = RandomDescriptor(rng);
  }
  for (const auto& [image_id, image] : scene->ground_truth.images) {
    Descriptors& descriptors = scene->database.descriptors[image_id];
    descriptors.num_cols = kDimension;
    descriptors.data.clear();
    descriptors.data.reserve(image.points2D.size() * kDimension);
    for (const Point2D& point2D : image.points2D) {
      const auto point = point_descriptors.find(point2D.point3D_id);
      if (point == point_descriptors.end()) {
        AppendBytes(RandomDescriptor(rng), &descriptors.data);
        continue;
      }
      std::vector<float> view = point->second;
      AddNoise(options.noise_sigma, rng, &view);
      AppendBytes(SiftShaped(std::move(view)), &descriptors.data);
    }
  }
}

}  // namespace ramap
