// Keypoints, descriptors, matches and two-view geometries: the contents of a COLMAP database.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "ramap/scene/camera.h"
#include "ramap/scene/image.h"
#include "ramap/scene/rig.h"
#include "ramap/scene/rigid3.h"

namespace ramap {

// COLMAP's bound on image ids, used in the pair id.
constexpr uint64_t kMaxNumImages = 2147483647;

// pair_id = i * 2147483647 + j with i < j (COLMAP's convention; the order of the arguments does
// not matter).
uint64_t ImagePairToPairId(uint32_t image_id1, uint32_t image_id2);
// The two image ids of a pair id, smaller first.
std::pair<uint32_t, uint32_t> PairIdToImagePair(uint64_t pair_id);
// Whether COLMAP stores the pair (image_id1, image_id2) in swapped order.
inline bool ShouldSwapImagePair(uint32_t image_id1, uint32_t image_id2) {
  return image_id1 > image_id2;
}

// Keypoints of one image as stored: rows x cols float32, cols in {2, 4, 6}; the first two columns
// are x, y in pixels; the rest (scale/orientation or an affine shape) are kept for round trips.
struct Keypoints {
  int num_cols = 2;
  std::vector<float> data;  // row-major, size() * num_cols values

  size_t size() const { return num_cols == 0 ? 0 : data.size() / num_cols; }
  Eigen::Vector2d xy(size_t row) const {
    return Eigen::Vector2d(data[row * num_cols], data[row * num_cols + 1]);
  }
};

// Descriptors of one image as stored: rows x cols uint8.
struct Descriptors {
  int num_cols = 128;
  std::vector<uint8_t> data;

  size_t size() const { return num_cols == 0 ? 0 : data.size() / num_cols; }
};

struct FeatureMatch {
  uint32_t point2D_idx1 = 0;
  uint32_t point2D_idx2 = 0;
};

// COLMAP's TwoViewGeometry::ConfigurationType (4.x added kCalibratedRig).
enum class TwoViewConfig : int {
  kUndefined = 0,
  kDegenerate = 1,
  kCalibrated = 2,
  kUncalibrated = 3,
  kPlanar = 4,
  kPanoramic = 5,
  kPlanarOrPanoramic = 6,
  kWatermark = 7,
  kMultiple = 8,
  kCalibratedRig = 9,  // COLMAP 4: the known relative pose of two cameras of one rig
};

// The verified geometry of an image pair, always held with image_id1 < image_id2 (the database
// order); cam2_from_cam1 maps camera-1 coordinates to camera-2 coordinates.
struct TwoViewGeometry {
  uint32_t image_id1 = 0;
  uint32_t image_id2 = 0;
  TwoViewConfig config = TwoViewConfig::kUndefined;
  std::vector<FeatureMatch> inlier_matches;
  Eigen::Matrix3d F = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Rigid3d cam2_from_cam1;
  // ramap's, not COLMAP's: the descriptor distance ratio (nearest / second nearest, in (0, 1];
  // lower is more distinctive) of each inlier match, in the order of inlier_matches, for the grid
  // selection of the relative-pose stage. Empty when unknown (COLMAP's matcher keeps none). Stored
  // in the extra table ramap_match_confidence, which COLMAP ignores.
  std::vector<float> inlier_ratios;
};

// The same geometry seen from the other image: ids, match columns, F, E, H and pose inverted.
TwoViewGeometry InvertTwoViewGeometry(const TwoViewGeometry& geometry);

// image id -> the unit bearing (camera frame) of each of its keypoints, by keypoint index.
using KeypointBearings = std::map<uint32_t, std::vector<Eigen::Vector3d>>;

// The generations of COLMAP's database schema (io/colmap_database_schema.h tells them apart):
// 3.8-3.9 (pose priors in the images table), 3.10-3.11 (a pose_priors table keyed by image) and
// 3.12-4.x (rigs, frames, pose_priors keyed by sensor data, typed descriptors).
enum class DatabaseGeneration { kColmap38, kColmap310, kColmap4 };

// Everything a COLMAP database holds, keyed by id (pairs by pair_id, smaller image id first).
struct FeatureDatabase {
  std::map<uint32_t, Camera> cameras;
  std::map<uint32_t, Image> images;  // points2D empty; keypoints are below
  std::map<uint32_t, Keypoints> keypoints;
  std::map<uint32_t, Descriptors> descriptors;
  std::map<uint64_t, std::vector<FeatureMatch>> matches;
  std::map<uint64_t, TwoViewGeometry> two_view_geometries;
  // Rigs and frames (3.12-4.x); empty: none stored, one rig per camera and one frame per image.
  Rigs rigs;
  Frames frames;
  // The schema it was read from (kColmap38 when built in memory).
  DatabaseGeneration generation = DatabaseGeneration::kColmap38;
  // The file it was read from (empty when built in memory), for messages.
  std::string source_path;
};

}  // namespace ramap
