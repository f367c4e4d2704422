// The synthetic scene builder: the same output for the same options, exact projections and epipolar
// geometry without noise, wrong matches, outlier and aliased pairs, loops and layouts as asked.
#include "ramap/synthetic/synthetic_scene.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <set>
#include <sstream>

#include "ramap/geometry/camera_projection.h"
#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {

SyntheticSceneOptions SmallOptions() {
  SyntheticSceneOptions options;
  options.num_images = 20;
  options.num_points = 800;
  options.seed = 3;
  return options;
}

SyntheticSceneOptions Layout(SyntheticLayout layout, SyntheticPath path) {
  SyntheticSceneOptions options = SmallOptions();
  options.layout = layout;
  options.path = path;
  if (path == SyntheticPath::kLoop) options.num_images = 40;
  return options;
}

std::vector<SyntheticSceneOptions> AllLayouts() {
  std::vector<SyntheticSceneOptions> all = {
      Layout(SyntheticLayout::kSequential, SyntheticPath::kLine),
      Layout(SyntheticLayout::kSequential, SyntheticPath::kCircle),
      Layout(SyntheticLayout::kSequential, SyntheticPath::kLoop),
      Layout(SyntheticLayout::kUnordered, SyntheticPath::kLine),
  };
  // A distorted camera, to exercise the projection of a model other than the pinhole.
  SyntheticSceneOptions distorted = Layout(SyntheticLayout::kSequential, SyntheticPath::kLine);
  distorted.camera.model = CameraModel::kOpenCV;
  distorted.camera.params = {500, 505, 320, 240, -0.15, 0.03, 0.001, -0.0005};
  all.push_back(distorted);
  return all;
}

std::string Describe(const SyntheticSceneOptions& options) {
  std::ostringstream out;
  out << "layout " << static_cast<int>(options.layout) << " path " << static_cast<int>(options.path)
      << " model " << CameraModelName(options.camera.model);
  return out.str();
}

double AngleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Checks every stored geometry but the listed outlier pairs against the true poses.
void ExpectGeometriesMatchTruth(const SyntheticScene& scene) {
  const std::set<uint64_t> outliers(scene.outlier_pair_ids.begin(), scene.outlier_pair_ids.end());
  const Camera& camera = scene.ground_truth.cameras.at(1);
  double worst_epipolar = 0.0;
  for (const auto& [pair_id, geometry] : scene.database.two_view_geometries) {
    ASSERT_LT(geometry.image_id1, geometry.image_id2);
    ASSERT_EQ(pair_id, ImagePairToPairId(geometry.image_id1, geometry.image_id2));
    ASSERT_TRUE(scene.database.matches.count(pair_id));
    if (outliers.count(pair_id)) continue;
    EXPECT_EQ(geometry.config, TwoViewConfig::kCalibrated);
    const Image& image1 = scene.ground_truth.images.at(geometry.image_id1);
    const Image& image2 = scene.ground_truth.images.at(geometry.image_id2);
    const Rigid3d expected = image2.cam_from_world * image1.cam_from_world.Inverse();
    EXPECT_LT(geometry.cam2_from_cam1.rotation.angularDistance(expected.rotation), 1e-12);
    EXPECT_NEAR(geometry.cam2_from_cam1.translation.norm(), 1.0, 1e-12);
    EXPECT_LT(AngleBetween(geometry.cam2_from_cam1.translation, expected.translation), 1e-12);
    // Every inlier is a true correspondence (same 3D point) and is among the raw matches.
    const std::vector<FeatureMatch>& raw = scene.database.matches.at(pair_id);
    std::set<std::pair<uint32_t, uint32_t>> raw_set;
    for (const FeatureMatch& m : raw) raw_set.insert({m.point2D_idx1, m.point2D_idx2});
    for (const FeatureMatch& match : geometry.inlier_matches) {
      EXPECT_TRUE(raw_set.count({match.point2D_idx1, match.point2D_idx2}));
      const Point2D& p1 = image1.points2D.at(match.point2D_idx1);
      const Point2D& p2 = image2.points2D.at(match.point2D_idx2);
      ASSERT_NE(p1.point3D_id, kInvalidPoint3DId);
      ASSERT_EQ(p1.point3D_id, p2.point3D_id);
      const Eigen::Vector3d x1 = PixelToBearing(camera, p1.xy);
      const Eigen::Vector3d x2 = PixelToBearing(camera, p2.xy);
      worst_epipolar = std::max(worst_epipolar, std::abs(x2.dot(geometry.E * x1)));
      if (camera.model == CameraModel::kPinhole) {
        // F on pixels, relative to the sizes involved (pixels are ~1e2, F entries ~1e-6).
        const Eigen::Vector3d h1(p1.xy.x(), p1.xy.y(), 1.0);
        const Eigen::Vector3d h2(p2.xy.x(), p2.xy.y(), 1.0);
        EXPECT_LT(std::abs(h2.dot(geometry.F * h1)) / (h2.norm() * geometry.F.norm() * h1.norm()),
                  1e-12);
      }
    }
    // The rest of the raw matches are wrong correspondences between clutter keypoints.
    EXPECT_EQ(raw_set.size(), raw.size()) << "a raw match appears twice";
    for (const FeatureMatch& m : raw) {
      const bool outlier1 = image1.points2D.at(m.point2D_idx1).point3D_id == kInvalidPoint3DId;
      const bool outlier2 = image2.points2D.at(m.point2D_idx2).point3D_id == kInvalidPoint3DId;
      EXPECT_EQ(outlier1, outlier2);
    }
  }
  EXPECT_LT(worst_epipolar, 1e-9);
}

TEST(Synthetic, SameSeedGivesIdenticalOutput) {
  SyntheticSceneOptions options = SmallOptions();
  options.num_outlier_pairs = 2;
  const SyntheticScene a = BuildSyntheticScene(options);
  const SyntheticScene b = BuildSyntheticScene(options);
  ASSERT_EQ(a.database.keypoints.size(), b.database.keypoints.size());
  for (const auto& [image_id, keypoints] : a.database.keypoints) {
    EXPECT_EQ(keypoints.data, b.database.keypoints.at(image_id).data);
  }
  ASSERT_EQ(a.database.matches.size(), b.database.matches.size());
  for (const auto& [pair_id, matches] : a.database.matches) {
    const std::vector<FeatureMatch>& other = b.database.matches.at(pair_id);
    ASSERT_EQ(matches.size(), other.size());
    for (size_t i = 0; i < matches.size(); ++i) {
      EXPECT_EQ(matches[i].point2D_idx1, other[i].point2D_idx1);
      EXPECT_EQ(matches[i].point2D_idx2, other[i].point2D_idx2);
    }
  }
  ASSERT_EQ(a.database.two_view_geometries.size(), b.database.two_view_geometries.size());
  for (const auto& [pair_id, geometry] : a.database.two_view_geometries) {
    EXPECT_EQ(geometry.E, b.database.two_view_geometries.at(pair_id).E);
  }
  ASSERT_EQ(a.ground_truth.points3D.size(), b.ground_truth.points3D.size());
  for (const auto& [id, point] : a.ground_truth.points3D) {
    EXPECT_EQ(point.xyz, b.ground_truth.points3D.at(id).xyz);
  }
  for (const auto& [id, image] : a.ground_truth.images) {
    EXPECT_EQ(image.cam_from_world.translation,
              b.ground_truth.images.at(id).cam_from_world.translation);
  }
  EXPECT_EQ(a.outlier_pair_ids, b.outlier_pair_ids);

  options.seed = 4;
  const SyntheticScene c = BuildSyntheticScene(options);
  EXPECT_NE(c.database.keypoints.at(1).data, a.database.keypoints.at(1).data);
}

TEST(Synthetic, NoiseFreeReprojectionIsExact) {
  for (SyntheticSceneOptions options : AllLayouts()) {
    SCOPED_TRACE(Describe(options));
    options.pixel_noise_sigma = 0.0;
    const SyntheticScene scene = BuildSyntheticScene(options);
    const Reconstruction& truth = scene.ground_truth;
    const Camera& camera = truth.cameras.at(1);
    ASSERT_EQ(truth.images.size(), static_cast<size_t>(options.num_images));
    ASSERT_GT(truth.points3D.size(), static_cast<size_t>(options.num_points / 4));
    double worst = 0.0;
    size_t num_observations = 0;
    for (const auto& [point3D_id, point] : truth.points3D) {
      ASSERT_GE(point.track.size(), 2u);
      for (const TrackElement& element : point.track) {
        const Image& image = truth.images.at(element.image_id);
        const Point2D& point2D = image.points2D.at(element.point2D_idx);
        ASSERT_EQ(point2D.point3D_id, point3D_id);
        const Eigen::Vector2d projection = ProjectToPixel(camera, image.cam_from_world * point.xyz);
        worst = std::max(worst, (projection - point2D.xy).norm());
        // The stored keypoint is the same observation in float32.
        const Eigen::Vector2d keypoint =
            scene.database.keypoints.at(element.image_id).xy(element.point2D_idx);
        EXPECT_EQ(keypoint.x(), static_cast<double>(static_cast<float>(point2D.xy.x())));
        EXPECT_EQ(keypoint.y(), static_cast<double>(static_cast<float>(point2D.xy.y())));
        ++num_observations;
      }
    }
    EXPECT_LT(worst, 1e-9);
    EXPECT_GT(num_observations, 2 * truth.points3D.size() - 1);
  }
}

TEST(Synthetic, TwoViewGeometriesAreTheTruePosesAndSatisfyTheEpipolarConstraint) {
  for (SyntheticSceneOptions options : AllLayouts()) {
    SCOPED_TRACE(Describe(options));
    options.pixel_noise_sigma = 0.0;
    options.outlier_ratio = 0.2;
    options.num_outlier_pairs = 2;
    const SyntheticScene scene = BuildSyntheticScene(options);
    EXPECT_FALSE(scene.database.two_view_geometries.empty());
    ExpectGeometriesMatchTruth(scene);
  }
}

TEST(Synthetic, OutlierRatioAndOutlierPairs) {
  SyntheticSceneOptions options = SmallOptions();
  options.outlier_ratio = 0.25;
  options.num_outlier_pairs = 3;
  const SyntheticScene scene = BuildSyntheticScene(options);
  ASSERT_EQ(scene.outlier_pair_ids.size(), 3u);
  size_t num_raw = 0;
  size_t num_inliers = 0;
  const std::set<uint64_t> outliers(scene.outlier_pair_ids.begin(), scene.outlier_pair_ids.end());
  for (const auto& [pair_id, geometry] : scene.database.two_view_geometries) {
    const auto [id1, id2] = PairIdToImagePair(pair_id);
    const Image& image1 = scene.ground_truth.images.at(id1);
    if (outliers.count(pair_id)) {
      // Nothing in an outlier pair observes a 3D point.
      EXPECT_EQ(geometry.inlier_matches.size(),
                static_cast<size_t>(options.num_outlier_pair_matches));
      for (const FeatureMatch& m : scene.database.matches.at(pair_id)) {
        EXPECT_EQ(image1.points2D.at(m.point2D_idx1).point3D_id, kInvalidPoint3DId);
      }
      continue;
    }
    num_raw += scene.database.matches.at(pair_id).size();
    num_inliers += geometry.inlier_matches.size();
  }
  ASSERT_GT(num_raw, 0u);
  EXPECT_NEAR(1.0 - static_cast<double>(num_inliers) / num_raw, 0.25, 0.01);
}

TEST(Synthetic, KeypointsAreInsideTheImage) {
  for (SyntheticSceneOptions options : AllLayouts()) {
    SCOPED_TRACE(Describe(options));
    options.pixel_noise_sigma = 2.0;
    options.num_outlier_pairs = 2;
    const SyntheticScene scene = BuildSyntheticScene(options);
    const Camera& camera = scene.database.cameras.at(1);
    for (const auto& [image_id, keypoints] : scene.database.keypoints) {
      ASSERT_EQ(keypoints.size(), scene.ground_truth.images.at(image_id).points2D.size());
      for (size_t row = 0; row < keypoints.size(); ++row) {
        const Eigen::Vector2d xy = keypoints.xy(row);
        ASSERT_GE(xy.x(), 0.0);
        ASSERT_GE(xy.y(), 0.0);
        ASSERT_LT(xy.x(), static_cast<double>(camera.width));
        ASSERT_LT(xy.y(), static_cast<double>(camera.height));
      }
    }
  }
}

TEST(Synthetic, ImagesAreNamedInOrder) {
  const SyntheticScene scene = BuildSyntheticScene(SmallOptions());
  EXPECT_EQ(scene.database.images.at(1).name, "frame_000001.png");
  EXPECT_EQ(scene.database.images.at(20).name, "frame_000020.png");
  EXPECT_EQ(scene.database.cameras.size(), 1u);
  EXPECT_EQ(scene.database.cameras.at(1).model, CameraModel::kPinhole);
}

TEST(Synthetic, SequentialOverlapGivesTheExpectedPairs) {
  for (int overlap : {1, 3, 6}) {
    SyntheticSceneOptions options = SmallOptions();
    options.overlap = overlap;
    options.num_points = 3000;
    const SyntheticScene scene = BuildSyntheticScene(options);
    std::set<std::pair<uint32_t, uint32_t>> expected;
    for (uint32_t i = 1; i <= 20; ++i) {
      for (uint32_t k = i + 1; k <= std::min<uint32_t>(20, i + overlap); ++k)
        expected.insert({i, k});
    }
    std::set<std::pair<uint32_t, uint32_t>> pairs;
    for (const auto& [pair_id, geometry] : scene.database.two_view_geometries) {
      pairs.insert({geometry.image_id1, geometry.image_id2});
      EXPECT_GE(geometry.inlier_matches.size(), static_cast<size_t>(options.min_num_inliers));
    }
    EXPECT_EQ(pairs, expected) << "overlap " << overlap;
  }
}

TEST(Synthetic, RevisitingPathsGetLoopPairs) {
  for (SyntheticPath path : {SyntheticPath::kLoop, SyntheticPath::kCircle}) {
    SyntheticSceneOptions options = Layout(SyntheticLayout::kSequential, path);
    options.overlap = 3;
    const SyntheticScene scene = BuildSyntheticScene(options);
    const uint32_t last = static_cast<uint32_t>(options.num_images);
    bool closes_loop = false;
    for (const auto& [pair_id, geometry] : scene.database.two_view_geometries) {
      if (geometry.image_id2 - geometry.image_id1 <= 3) continue;
      // A loop pair joins the end of the path to its start.
      EXPECT_LE(geometry.image_id1, 3u);
      EXPECT_GE(geometry.image_id2, last - 3);
      closes_loop = closes_loop || (geometry.image_id1 == 1 && geometry.image_id2 == last);
    }
    EXPECT_TRUE(closes_loop) << "path " << static_cast<int>(path);
  }
}

TEST(Synthetic, AliasedPairsAreConsistentWithARotationOffByTheGivenAngles) {
  SyntheticSceneOptions options = SmallOptions();
  options.num_aliased_pairs = 4;
  const SyntheticScene scene = BuildSyntheticScene(options);
  ASSERT_EQ(scene.aliased_pair_ids.size(), 4u);
  for (const uint64_t pair_id : scene.aliased_pair_ids) {
    const TwoViewGeometry& geometry = scene.database.two_view_geometries.at(pair_id);
    const Rigid3d truth = scene.ground_truth.images.at(geometry.image_id2).cam_from_world *
                          scene.ground_truth.images.at(geometry.image_id1).cam_from_world.Inverse();
    const double off_deg =
        geometry.cam2_from_cam1.rotation.angularDistance(truth.rotation) * 180.0 / M_PI;
    EXPECT_GE(off_deg, 0.0);
    EXPECT_LE(off_deg, 40.0 + 1e-9);
    // The matches obey the aliased pose, not the true one: tiny epipolar residuals under F up to
    // the pixel noise.
    const Keypoints& k1 = scene.database.keypoints.at(geometry.image_id1);
    const Keypoints& k2 = scene.database.keypoints.at(geometry.image_id2);
    ASSERT_GE(geometry.inlier_matches.size(), 15u);
    for (const FeatureMatch& match : geometry.inlier_matches) {
      const Eigen::Vector3d x1 = k1.xy(match.point2D_idx1).homogeneous();
      const Eigen::Vector3d x2 = k2.xy(match.point2D_idx2).homogeneous();
      const Eigen::Vector3d line = geometry.F * x1;
      EXPECT_LT(std::abs(x2.dot(line)) / line.head<2>().norm(), 5.0);  // px, 0.5 px noise
    }
  }
  // A ratio of the matched pairs, when it asks for more.
  options.num_aliased_pairs = 0;
  options.aliased_pair_ratio = 0.1;
  const SyntheticScene by_ratio = BuildSyntheticScene(options);
  EXPECT_NEAR(
      static_cast<double>(by_ratio.aliased_pair_ids.size()),
      0.1 * (by_ratio.database.two_view_geometries.size() - by_ratio.aliased_pair_ids.size()), 1.0);
}

// Aliased pairs as a facade's repeat gives them: a few frames apart, the true rotation with the
// second camera moved, and matches that start from the first image's observations of scene points
// (so that they join those points' tracks).
TEST(Synthetic, AliasedPairsNearbyShiftedAndOnTracks) {
  SyntheticSceneOptions options = SmallOptions();
  options.num_images = 40;
  const SyntheticScene scene = BuildSyntheticScene(test::WithFacadeRepeats(options, 5, 2.0));
  ASSERT_EQ(scene.aliased_pair_ids.size(), 5u);
  for (const uint64_t pair_id : scene.aliased_pair_ids) {
    const TwoViewGeometry& geometry = scene.database.two_view_geometries.at(pair_id);
    EXPECT_LE(geometry.image_id2 - geometry.image_id1, 8u);
    const Rigid3d truth = scene.ground_truth.images.at(geometry.image_id2).cam_from_world *
                          scene.ground_truth.images.at(geometry.image_id1).cam_from_world.Inverse();
    EXPECT_LT(geometry.cam2_from_cam1.rotation.angularDistance(truth.rotation), 1e-9);
    // The stored translation is a direction: that of the true one moved by 2 m, so it misses the
    // true direction, and the true translation lies within 2 m of its line.
    const Eigen::Vector3d stored = geometry.cam2_from_cam1.translation.normalized();
    EXPECT_GT(stored.cross(truth.translation.normalized()).norm(), 1e-3);
    EXPECT_LE((truth.translation - truth.translation.dot(stored) * stored).norm(), 2.0 + 1e-9);
    const Image& first = scene.ground_truth.images.at(geometry.image_id1);
    std::set<uint32_t> distinct;
    for (const FeatureMatch& match : geometry.inlier_matches) {
      EXPECT_NE(first.points2D.at(match.point2D_idx1).point3D_id, kInvalidPoint3DId);
      distinct.insert(match.point2D_idx1);
    }
    EXPECT_EQ(distinct.size(), geometry.inlier_matches.size());
  }
}

// A landmark whose back looks like its front: each symmetric pair joins views from about opposite
// sides of the orbit, and its matches obey the second camera turned 180 degrees about the vertical
// axis, so its rotation is about 180 degrees off the true one and about that of a near neighbour.
TEST(Synthetic, SymmetricPairsObeyTheViewTurnedAroundTheObject) {
  SyntheticSceneOptions options = Layout(SyntheticLayout::kSequential, SyntheticPath::kCircle);
  options.num_images = 36;
  options.num_aliased_pairs = 6;
  options.aliased_matches_on_tracks = true;
  options.aliased_symmetric = true;
  const SyntheticScene scene = BuildSyntheticScene(options);
  ASSERT_EQ(scene.aliased_pair_ids.size(), 6u);
  const Rigid3d turn(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY())),
                     Eigen::Vector3d::Zero());
  for (const uint64_t pair_id : scene.aliased_pair_ids) {
    const TwoViewGeometry& geometry = scene.database.two_view_geometries.at(pair_id);
    const Rigid3d& pose1 = scene.ground_truth.images.at(geometry.image_id1).cam_from_world;
    const Rigid3d& pose2 = scene.ground_truth.images.at(geometry.image_id2).cam_from_world;
    const Rigid3d truth = pose2 * pose1.Inverse();
    EXPECT_GT(geometry.cam2_from_cam1.rotation.angularDistance(truth.rotation), 120.0 * M_PI / 180);
    const Rigid3d turned = pose2 * turn * pose1.Inverse();
    EXPECT_LT(geometry.cam2_from_cam1.rotation.angularDistance(turned.rotation), 1e-9);
    EXPECT_LT(geometry.cam2_from_cam1.rotation.angularDistance(Eigen::Quaterniond::Identity()),
              40.0 * M_PI / 180);
    EXPECT_GE(geometry.inlier_matches.size(), 15u);
  }
  options.layout = SyntheticLayout::kSequential;
  options.path = SyntheticPath::kLine;
  test::ExpectInputError([&] { BuildSyntheticScene(options); },
                         {"--Synthetic.aliased_symmetric", "unordered"});
}

TEST(Synthetic, ViewDistanceLimitsTracksAndFrameGapLimitsLoops) {
  SyntheticSceneOptions options = Layout(SyntheticLayout::kSequential, SyntheticPath::kLoop);
  options.num_images = 60;
  options.overlap = 3;
  options.loop_min_frame_gap = 50;
  options.max_view_distance = 12.0;
  const SyntheticScene scene = BuildSyntheticScene(options);
  for (const auto& [id, point] : scene.ground_truth.points3D) {
    for (const TrackElement& element : point.track) {
      const Rigid3d& pose = scene.ground_truth.images.at(element.image_id).cam_from_world;
      EXPECT_LE((pose * point.xyz).norm(), 12.0 + 1e-9);
    }
  }
  bool has_loop = false;
  for (const auto& [pair_id, geometry] : scene.database.two_view_geometries) {
    if (geometry.image_id2 - geometry.image_id1 <= 3) continue;
    EXPECT_GT(geometry.image_id2 - geometry.image_id1, 50u);
    has_loop = true;
  }
  EXPECT_TRUE(has_loop);
}

// A straight road along +z: facade points stand beside it, none in the middle, and the scene is
// still a matched sequence.
TEST(Synthetic, FacadesPutThePointsBesideTheRoad) {
  SyntheticSceneOptions options = Layout(SyntheticLayout::kSequential, SyntheticPath::kLine);
  options.facade_distance = 6.0;
  options.facade_roughness = 0.1;
  options.rotation_jitter_deg = 0.2;
  const SyntheticScene scene = BuildSyntheticScene(options);
  ASSERT_GT(scene.ground_truth.points3D.size(), 200u);
  int left = 0, right = 0;
  for (const auto& [id, point] : scene.ground_truth.points3D) {
    // The path's jitter (0.2 deg, 5 cm) moves a facade by a few decimetres at 30 m ahead.
    EXPECT_NEAR(std::abs(point.xyz.x()), 6.0, 0.7) << point.xyz.transpose();
    EXPECT_LT(point.xyz.y(), 1.5 + 1.0);
    (point.xyz.x() < 0 ? left : right)++;
  }
  EXPECT_GT(left, 50);
  EXPECT_GT(right, 50);
  EXPECT_EQ(scene.database.two_view_geometries.size(), scene.database.matches.size());
}

// Scale and orientation, or an affine shape, are stored beside x and y without changing anything
// else of the scene.
TEST(Synthetic, ExtraKeypointColumnsLeaveTheSceneAsItWas) {
  const SyntheticSceneOptions options = SmallOptions();
  const SyntheticScene plain = BuildSyntheticScene(options);
  for (const int columns : {4, 6}) {
    SyntheticSceneOptions with_shapes = options;
    with_shapes.keypoint_columns = columns;
    const SyntheticScene scene = BuildSyntheticScene(with_shapes);
    for (const auto& [image_id, keypoints] : scene.database.keypoints) {
      const Keypoints& xy_only = plain.database.keypoints.at(image_id);
      ASSERT_EQ(keypoints.num_cols, columns);
      ASSERT_EQ(keypoints.size(), xy_only.size());
      for (size_t k = 0; k < keypoints.size(); ++k) {
        EXPECT_EQ(keypoints.xy(k), xy_only.xy(k));
        const float* shape = &keypoints.data[k * columns + 2];
        const double scale = columns == 4 ? shape[0] : std::hypot(shape[0], shape[2]);
        EXPECT_GE(scale, 1.5 - 1e-5);
        EXPECT_LE(scale, 12.0 + 1e-5);
      }
    }
    EXPECT_EQ(scene.database.matches.size(), plain.database.matches.size());
    EXPECT_EQ(scene.ground_truth.points3D.size(), plain.ground_truth.points3D.size());
  }
}

TEST(Synthetic, UnorderedPairsShareEnoughPoints) {
  SyntheticSceneOptions options = Layout(SyntheticLayout::kUnordered, SyntheticPath::kLine);
  options.outlier_ratio = 0.0;
  options.min_shared_points = 40;
  const SyntheticScene scene = BuildSyntheticScene(options);
  ASSERT_FALSE(scene.database.matches.empty());
  for (const auto& [pair_id, matches] : scene.database.matches) {
    EXPECT_GE(matches.size(), 40u);
  }
  // Views from opposite sides of the object see different halves of it: not every pair matches.
  EXPECT_LT(scene.database.matches.size(), 20u * 19u / 2u);
  // The matched pairs are exactly those sharing enough points in the truth.
  size_t expected = 0;
  for (uint32_t i = 1; i <= 20; ++i) {
    std::set<uint64_t> seen;
    for (const Point2D& p : scene.ground_truth.images.at(i).points2D) seen.insert(p.point3D_id);
    for (uint32_t k = i + 1; k <= 20; ++k) {
      size_t shared = 0;
      for (const Point2D& p : scene.ground_truth.images.at(k).points2D) {
        shared += p.point3D_id != kInvalidPoint3DId && seen.count(p.point3D_id);
      }
      expected += shared >= 40;
    }
  }
  EXPECT_EQ(scene.database.matches.size(), expected);
}

TEST(Synthetic, BadOptionsAreRejected) {
  auto expect_rejected = [](const std::function<void(SyntheticSceneOptions&)>& change) {
    SyntheticSceneOptions options;
    change(options);
    EXPECT_THROW(options.Check(), InputError);
    EXPECT_THROW(BuildSyntheticScene(options), InputError);
  };
  EXPECT_NO_THROW(SyntheticSceneOptions().Check());
  expect_rejected([](SyntheticSceneOptions& o) { o.num_images = 1; });
  expect_rejected([](SyntheticSceneOptions& o) { o.num_points = 0; });
  expect_rejected([](SyntheticSceneOptions& o) { o.pixel_noise_sigma = -1.0; });
  expect_rejected([](SyntheticSceneOptions& o) { o.outlier_ratio = 1.0; });
  expect_rejected([](SyntheticSceneOptions& o) { o.overlap = 0; });
  expect_rejected([](SyntheticSceneOptions& o) { o.max_depth = o.min_depth; });
  expect_rejected([](SyntheticSceneOptions& o) { o.camera.params = {500, 320, 240}; });
  expect_rejected([](SyntheticSceneOptions& o) { o.path = SyntheticPath::kGiven; });
  expect_rejected([](SyntheticSceneOptions& o) { o.keypoint_columns = 3; });
  expect_rejected([](SyntheticSceneOptions& o) { o.facade_height = 0.0; });
  expect_rejected([](SyntheticSceneOptions& o) { o.facade_distance = -1.0; });
}

// Reads the first `max_poses` lines of a KITTI odometry pose file (camera-to-world 3x4 rows).
std::vector<Rigid3d> ReadKittiPoses(const std::string& path, size_t max_poses) {
  std::vector<Rigid3d> poses;
  std::ifstream file(path);
  std::string line;
  while (poses.size() < max_poses && std::getline(file, line)) {
    std::istringstream in(line);
    Eigen::Matrix<double, 3, 4> world_from_cam;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) in >> world_from_cam(r, c);
    }
    if (!in) break;
    const Eigen::Quaterniond rotation(world_from_cam.leftCols<3>());
    poses.push_back(Rigid3d(rotation.normalized(), world_from_cam.col(3)).Inverse());
  }
  return poses;
}

TEST(Synthetic, KittiTrajectoryAsGivenPoses) {
  RAMAP_REQUIRE_SHARED_DATA(path, "gt_trajectories/kitti_odometry_poses/07.txt");
  SyntheticSceneOptions options;
  options.path = SyntheticPath::kGiven;
  options.given_poses = ReadKittiPoses(path, 100);
  ASSERT_EQ(options.given_poses.size(), 100u);
  options.num_images = 0;
  options.num_points = 3000;
  options.pixel_noise_sigma = 0.0;
  // KITTI's rectified grey camera, roughly.
  options.camera.width = 1241;
  options.camera.height = 376;
  options.camera.params = {718.9, 718.9, 607.2, 185.2};
  const SyntheticScene scene = BuildSyntheticScene(options);
  ASSERT_EQ(scene.ground_truth.images.size(), 100u);
  for (uint32_t i = 1; i <= 100; ++i) {
    const Rigid3d& pose = scene.ground_truth.images.at(i).cam_from_world;
    EXPECT_LT((pose.translation - options.given_poses[i - 1].translation).norm(), 1e-12);
  }
  // Consecutive frames are all verified pairs (the car never jumps out of view).
  for (uint32_t i = 1; i < 100; ++i) {
    EXPECT_TRUE(scene.database.two_view_geometries.count(ImagePairToPairId(i, i + 1))) << i;
  }
  ExpectGeometriesMatchTruth(scene);
  size_t num_observations = 0;
  for (const auto& [id, point] : scene.ground_truth.points3D)
    num_observations += point.track.size();
  std::cout << "KITTI 07, 100 frames: " << scene.ground_truth.points3D.size() << " points3D, "
            << num_observations << " observations, " << scene.database.two_view_geometries.size()
            << " verified pairs\n";
}

// KITTI 07 ends where it began: the whole trajectory must get loop pairs joining its end to its
// start, and no others (the rest of the route is never driven twice).
TEST(Synthetic, KittiLoopClosureBecomesLoopPairs) {
  RAMAP_REQUIRE_SHARED_DATA(path, "gt_trajectories/kitti_odometry_poses/07.txt");
  SyntheticSceneOptions options;
  options.path = SyntheticPath::kGiven;
  options.given_poses = ReadKittiPoses(path, 100000);
  ASSERT_EQ(options.given_poses.size(), 1101u);
  options.num_images = 0;
  options.num_points = 6000;
  options.camera.width = 1241;
  options.camera.height = 376;
  options.camera.params = {718.9, 718.9, 607.2, 185.2};
  const SyntheticScene scene = BuildSyntheticScene(options);
  size_t num_loop_pairs = 0;
  for (const auto& [pair_id, geometry] : scene.database.two_view_geometries) {
    if (geometry.image_id2 - geometry.image_id1 <= static_cast<uint32_t>(options.overlap)) continue;
    ++num_loop_pairs;
    EXPECT_LE(geometry.image_id1, 50u);
    EXPECT_GE(geometry.image_id2, 1000u);
  }
  // Measured: 387 pairs between frames 1-27 and 1053-1080.
  EXPECT_GT(num_loop_pairs, 50u);
  std::cout << "KITTI 07: " << num_loop_pairs << " loop pairs\n";
}

}  // namespace
}  // namespace ramap
