// SIFT-like descriptors for a synthetic scene, so that retrieval and descriptor matching can be
// tested and timed at thousands of images without photos: each 3D point has its own random
// descriptor, and each view of it adds its own noise, as a feature seen again from another place
// looks a little different. Keypoints on no 3D point get descriptors of their own.
#pragma once

#include <cstdint>

#include "ramap/synthetic/synthetic_scene.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct SyntheticDescriptorOptions {
  // Noise (uniform, of this standard deviation) added to each of the 128 values of a view's
  // descriptor (the values are SIFT's: 8-bit, L2 norm about 512, so two unrelated descriptors are
  // about 430 apart and a noise of 8 moves a view about 90 from its point's descriptor: the ratio
  // test passes it).
  double noise_sigma = 8.0;
  uint64_t seed = 1;

  void Check() const;  // throws InputError naming the option
};

// Its options (--Synthetic.descriptor_noise), each declared once with its range and help
// (util/option_table.h): the command line, Check() and Python read them.
const OptionTable<SyntheticDescriptorOptions>& SyntheticDescriptorOptionTable();

// Fills scene->database.descriptors: one 128-column row per keypoint of every image.
void AddSyntheticDescriptors(const SyntheticDescriptorOptions& options, SyntheticScene* scene);

}  // namespace ramap
