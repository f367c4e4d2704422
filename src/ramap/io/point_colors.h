// Colours of a model's 3D points from the images they were seen in, as COLMAP's mapper stores
// them: the mean over a point's observations of the image colour at each keypoint.
#pragma once

#include <string>
#include <vector>

#include "ramap/scene/reconstruction.h"

namespace ramap {

struct PointColorSummary {
  int num_images_read = 0;
  std::vector<std::string> unreadable_images;  // names under image_path that could not be read
};

// Reads every registered image as image_path/NAME (any format OpenCV reads) and sets each point's
// colour to the mean RGB of its observations, sampled at the keypoint's pixel (COLMAP's convention:
// pixel (0, 0) covers [0, 1)). Images that cannot be read are listed, not fatal: their
// observations do not count, and a point seen by none keeps its colour.
PointColorSummary ColorPointsFromImages(const std::string& image_path,
                                        Reconstruction* reconstruction);

// The same for every model of a run, the images read and unreadable summed over them.
PointColorSummary ColorModelsFromImages(const std::string& image_path,
                                        std::vector<Reconstruction>* models);

}  // namespace ramap
