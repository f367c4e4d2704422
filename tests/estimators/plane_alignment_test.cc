// PrincipalPlaneAlignment: a model's points moved onto z = 0 about their centroid, the widest
// spread along x, the first camera above, and models too small to have a plane.
#include "ramap/estimators/plane_alignment.h"

#include <gtest/gtest.h>

#include <random>

#include "test_support.h"

namespace ramap {
namespace {

// Points on a tilted plane through (3, -2, 5), spread 10 units along `wide` and 4 along the other
// in-plane axis, and one camera 6 units from the plane on the side of `normal` (or the other).
struct PlaneModel {
  Reconstruction model;
  Eigen::Vector3d normal, wide;
};

PlaneModel TiltedPlane(bool camera_on_normal_side) {
  PlaneModel plane;
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(0.8, Eigen::Vector3d(1, 2, -1).normalized()));
  plane.normal = tilt * Eigen::Vector3d::UnitZ();
  plane.wide = tilt * Eigen::Vector3d::UnitX();
  const Eigen::Vector3d narrow = tilt * Eigen::Vector3d::UnitY();
  const Eigen::Vector3d middle(3, -2, 5);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1, 1);
  for (uint64_t id = 1; id <= 200; ++id) {
    plane.model.points3D[id].xyz = middle + 10 * u(rng) * plane.wide + 4 * u(rng) * narrow;
  }
  const Eigen::Vector3d center = middle + (camera_on_normal_side ? 6.0 : -6.0) * plane.normal;
  Image image;
  image.image_id = 1;
  image.camera_id = 1;
  image.name = "above.png";
  image.cam_from_world = Rigid3d(tilt.conjugate(), -(tilt.conjugate() * center));
  plane.model.images[1] = image;
  plane.model.cameras[1] = test::VgaPinholeCamera();
  return plane;
}

Eigen::Vector3d Centroid(const Reconstruction& model, const Sim3d& transform) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& [id, point] : model.points3D) sum += transform * point.xyz;
  return sum / static_cast<double>(model.points3D.size());
}

// The plane is exact: only rounding of the 3x3 eigensolver and of the sums (1e-12 of a 10-unit
// scene) separates the points from z = 0 and the centroid from the origin.
constexpr double kRounding = 1e-10;

TEST(PlaneAlignment, PointsOnAPlaneLandOnZeroAboutTheirCentroid) {
  for (const bool camera_on_normal_side : {true, false}) {
    const PlaneModel plane = TiltedPlane(camera_on_normal_side);
    const Sim3d aligned = PrincipalPlaneAlignment(plane.model, "model");
    EXPECT_EQ(aligned.scale, 1.0);
    EXPECT_LT(Centroid(plane.model, aligned).norm(), kRounding);
    double spread_x = 0, spread_y = 0;
    for (const auto& [id, point] : plane.model.points3D) {
      const Eigen::Vector3d moved = aligned * point.xyz;
      EXPECT_NEAR(moved.z(), 0.0, kRounding) << "point " << id;
      spread_x += moved.x() * moved.x();
      spread_y += moved.y() * moved.y();
    }
    // The widest spread (10 against 4 units) is along x.
    EXPECT_GT(spread_x, 3 * spread_y);
    // 200 random points' principal axis is within a few degrees of the axis they were spread
    // along (cos 8 deg = 0.99).
    EXPECT_GT(std::abs((aligned.rotation * plane.wide).x()), 0.99);
    // Whichever side the camera was on, it ends 6 units above the plane: +Z is up.
    const Eigen::Vector3d camera = aligned * CameraCenter(plane.model.images.at(1).cam_from_world);
    EXPECT_NEAR(camera.z(), 6.0, kRounding)
        << "camera on the normal's side: " << camera_on_normal_side;
    // A rotation, not a reflection.
    EXPECT_NEAR(aligned.rotation.toRotationMatrix().determinant(), 1.0, 1e-12);
  }
}

TEST(PlaneAlignment, TooFewPointsOrNoImageIsAnError) {
  PlaneModel plane = TiltedPlane(true);
  Reconstruction two_points = plane.model;
  while (two_points.points3D.size() > 2) two_points.points3D.erase(two_points.points3D.begin());
  test::ExpectInputError([&] { PrincipalPlaneAlignment(two_points, "sparse/0"); },
                         {"sparse/0", "2 3D points"});
  Reconstruction no_image = plane.model;
  no_image.images.clear();
  test::ExpectInputError([&] { PrincipalPlaneAlignment(no_image, "sparse/0"); },
                         {"sparse/0", "0 images"});
}

}  // namespace
}  // namespace ramap
