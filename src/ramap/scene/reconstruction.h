// A sparse model as COLMAP writes it: cameras, registered images and 3D points with tracks.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ramap/scene/camera.h"
#include "ramap/scene/image.h"
#include "ramap/scene/rig.h"

namespace ramap {

struct TrackElement {
  uint32_t image_id = 0;
  uint32_t point2D_idx = 0;
};

struct Point3D {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  Eigen::Matrix<uint8_t, 3, 1> color = Eigen::Matrix<uint8_t, 3, 1>::Zero();
  double error = -1.0;  // mean reprojection error in pixels; -1 when unknown (COLMAP's default)
  std::vector<TrackElement> track;
};

// Only registered images are held in `images`.
struct Reconstruction {
  std::map<uint32_t, Camera> cameras;
  std::map<uint32_t, Image> images;
  std::map<uint64_t, Point3D> points3D;
  // A COLMAP 4 model's rigs and frames as read (io/colmap_model_rigs.h); empty: one rig per camera
  // and one frame per image. The images' poses are the truth: frames' poses follow them on writing.
  Rigs rigs;
  Frames frames;
};

// A model of cameras alone: one image per pose (ids 1, 2, ... in name order), all seen through
// `camera` (given id 1), no points. What a trajectory or ground truth is drawn and scored as.
Reconstruction ModelOfPoses(const std::map<std::string, Rigid3d>& cam_from_world,
                            const Camera& camera);

}  // namespace ramap
