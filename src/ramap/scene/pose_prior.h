// Measured camera centres (GPS, a survey) in one local metric frame, the frame in which a model
// aligned to its priors is written.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <optional>

#include "ramap/scene/geodetic_point.h"

namespace ramap {

struct PosePrior {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();     // metres, local frame
  Eigen::Vector3d std_dev_m = Eigen::Vector3d::Ones();  // per axis of the local frame
};

struct PosePriors {
  // When set, the local frame is east-north-up about this origin (GeoJSON can be written);
  // otherwise it is the metric frame the priors were given in (PriorCoordinates::kXyz).
  std::optional<GeodeticPoint> origin;
  std::map<uint32_t, PosePrior> by_image;
};

}  // namespace ramap
