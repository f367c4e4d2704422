#include "ramap/geometry/camera_projection.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "ramap/util/error.h"

namespace ramap {
namespace {

Camera MakeCamera(CameraModel model, std::vector<double> params) {
  Camera camera;
  camera.camera_id = 1;
  camera.model = model;
  camera.width = 640;
  camera.height = 480;
  camera.params = std::move(params);
  return camera;
}

// Realistic parameters for every model: distortion of the size calibrations report.
std::vector<Camera> AllModelCameras() {
  return {
      MakeCamera(CameraModel::kSimplePinhole, {500, 320, 240}),
      MakeCamera(CameraModel::kPinhole, {500, 520, 321.5, 239.5}),
      MakeCamera(CameraModel::kSimpleRadial, {500, 320, 240, -0.12}),
      MakeCamera(CameraModel::kRadial, {500, 320, 240, -0.15, 0.03}),
      MakeCamera(CameraModel::kOpenCV, {500, 510, 320, 240, -0.2, 0.05, 0.001, -0.0005}),
      MakeCamera(CameraModel::kOpenCVFisheye, {300, 302, 320, 240, 0.05, -0.01, 0.002, -0.0003}),
      MakeCamera(CameraModel::kFullOpenCV,
                 {500, 510, 320, 240, -0.2, 0.05, 0.001, -0.0005, 0.01, 0.02, 0.003, 0.001}),
      MakeCamera(CameraModel::kFOV, {400, 405, 320, 240, 0.9}),
      MakeCamera(CameraModel::kSimpleRadialFisheye, {300, 320, 240, 0.04}),
      MakeCamera(CameraModel::kRadialFisheye, {300, 320, 240, 0.05, -0.01}),
      MakeCamera(CameraModel::kThinPrismFisheye, {300, 302, 320, 240, 0.05, -0.01, 0.001, -0.0005,
                                                  0.002, -0.0003, 0.0005, -0.0003}),
  };
}

double AngleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

TEST(CameraProjection, RoundTripRecoversTheDirectionForEveryModel) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::vector<Camera> cameras = AllModelCameras();
  ASSERT_EQ(cameras.size(), 11u);
  for (const Camera& camera : cameras) {
    SCOPED_TRACE(CameraModelName(camera.model));
    ASSERT_NO_THROW(CheckCameraParams(camera, "test"));
    // Perspective lenses up to ~35 degrees off axis (the image corner), fisheyes to 85 degrees.
    const double max_angle = IsFisheyeModel(camera.model) ? 85.0 * M_PI / 180 : 35.0 * M_PI / 180;
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i) {
      const double angle = max_angle * std::sqrt(unit(rng));
      const double azimuth = 2 * M_PI * unit(rng);
      const double distance = 0.5 + 20 * unit(rng);
      const Eigen::Vector3d direction(std::sin(angle) * std::cos(azimuth),
                                      std::sin(angle) * std::sin(azimuth), std::cos(angle));
      const Eigen::Vector2d pixel = ProjectToPixel(camera, distance * direction);
      ASSERT_TRUE(pixel.allFinite());
      const Eigen::Vector3d bearing = PixelToBearing(camera, pixel);
      ASSERT_TRUE(bearing.allFinite()) << pixel.transpose();
      EXPECT_NEAR(bearing.norm(), 1.0, 1e-12);
      worst = std::max(worst, AngleBetween(bearing, direction));
    }
    EXPECT_LT(worst, 1e-9);
  }
}

TEST(CameraProjection, OpticalAxisMapsToThePrincipalPoint) {
  for (const Camera& camera : AllModelCameras()) {
    SCOPED_TRACE(CameraModelName(camera.model));
    const Eigen::Vector2d pixel = ProjectToPixel(camera, Eigen::Vector3d(0, 0, 3));
    const bool single = camera.params.size() == 3 || camera.model == CameraModel::kSimpleRadial ||
                        camera.model == CameraModel::kRadial ||
                        camera.model == CameraModel::kSimpleRadialFisheye ||
                        camera.model == CameraModel::kRadialFisheye;
    const int c = single ? 1 : 2;
    EXPECT_NEAR(pixel.x(), camera.params[c], 1e-12);
    EXPECT_NEAR(pixel.y(), camera.params[c + 1], 1e-12);
    EXPECT_LT(AngleBetween(PixelToBearing(camera, pixel), Eigen::Vector3d::UnitZ()), 1e-12);
  }
}

// Hand-computed values, so that a wrong but invertible formula cannot pass the round trip alone.
TEST(CameraProjection, MatchesHandComputedValues) {
  {
    // r^2 = 0.05, 1 + k r^2 = 0.995.
    const Camera camera = MakeCamera(CameraModel::kSimpleRadial, {500, 320, 240, -0.1});
    const Eigen::Vector2d pixel = ProjectToPixel(camera, Eigen::Vector3d(0.4, 0.2, 2.0));
    EXPECT_NEAR(pixel.x(), 500 * 0.2 * 0.995 + 320, 1e-9);
    EXPECT_NEAR(pixel.y(), 500 * 0.1 * 0.995 + 240, 1e-9);
  }
  {
    // u = 0.2, v = -0.1: radial 1 + k1 0.05 + k2 0.0025; tangential 2 p1 uv + p2 (r2 + 2u^2).
    const double k1 = -0.2, k2 = 0.05, p1 = 0.001, p2 = -0.0005;
    const Camera camera = MakeCamera(CameraModel::kOpenCV, {500, 510, 320, 240, k1, k2, p1, p2});
    const Eigen::Vector2d pixel = ProjectToPixel(camera, Eigen::Vector3d(0.2, -0.1, 1.0));
    const double radial = 1 + k1 * 0.05 + k2 * 0.0025;
    EXPECT_NEAR(pixel.x(), 500 * (0.2 * radial + 2 * p1 * -0.02 + p2 * (0.05 + 0.08)) + 320, 1e-9);
    EXPECT_NEAR(pixel.y(), 510 * (-0.1 * radial + 2 * p2 * -0.02 + p1 * (0.05 + 0.02)) + 240, 1e-9);
  }
  {
    // 45 degrees off axis: theta = pi/4, thetad = theta (1 + k1 theta^2).
    const Camera camera =
        MakeCamera(CameraModel::kOpenCVFisheye, {300, 300, 320, 240, 0.1, 0.0, 0.0, 0.0});
    const Eigen::Vector2d pixel = ProjectToPixel(camera, Eigen::Vector3d(1.0, 0.0, 1.0));
    const double theta = M_PI / 4;
    EXPECT_NEAR(pixel.x(), 300 * theta * (1 + 0.1 * theta * theta) + 320, 1e-9);
    EXPECT_NEAR(pixel.y(), 240, 1e-12);
  }
  {
    // Devernay-Faugeras: r_d = atan(2 r tan(omega / 2)) / omega.
    const double omega = 0.9;
    const Camera camera = MakeCamera(CameraModel::kFOV, {400, 400, 320, 240, omega});
    const Eigen::Vector2d pixel = ProjectToPixel(camera, Eigen::Vector3d(0.0, 1.0, 2.0));
    EXPECT_NEAR(pixel.x(), 320, 1e-12);
    EXPECT_NEAR(pixel.y(), 400 * std::atan(2 * 0.5 * std::tan(omega / 2)) / omega + 240, 1e-9);
  }
  {
    // Thin prism on the equidistant coordinates: only sx1, sy1 set; uu = theta = pi/4.
    const Camera camera = MakeCamera(CameraModel::kThinPrismFisheye,
                                     {300, 310, 320, 240, 0, 0, 0, 0, 0, 0, 0.01, -0.02});
    const Eigen::Vector2d pixel = ProjectToPixel(camera, Eigen::Vector3d(2.0, 0.0, 2.0));
    const double theta = M_PI / 4;
    EXPECT_NEAR(pixel.x(), 300 * (theta + 0.01 * theta * theta) + 320, 1e-9);
    EXPECT_NEAR(pixel.y(), 310 * (-0.02 * theta * theta) + 240, 1e-9);
  }
  {
    // RADIAL_FISHEYE: thetad = theta (1 + k1 theta^2 + k2 theta^4) at 30 degrees.
    const Camera camera = MakeCamera(CameraModel::kRadialFisheye, {300, 320, 240, 0.05, -0.01});
    const double theta = M_PI / 6;
    const Eigen::Vector2d pixel =
        ProjectToPixel(camera, Eigen::Vector3d(0.0, std::sin(theta), std::cos(theta)));
    const double t2 = theta * theta;
    EXPECT_NEAR(pixel.y(), 300 * theta * (1 + 0.05 * t2 - 0.01 * t2 * t2) + 240, 1e-9);
  }
}

TEST(CameraProjection, PerspectiveModelsRejectPointsBehindTheCamera) {
  const Camera camera = MakeCamera(CameraModel::kPinhole, {500, 500, 320, 240});
  EXPECT_FALSE(ProjectToPixel(camera, Eigen::Vector3d(0.1, 0.2, -1.0)).allFinite());
  EXPECT_FALSE(ProjectToPixel(camera, Eigen::Vector3d(0.1, 0.2, 0.0)).allFinite());
}

TEST(CameraProjection, FisheyeRoundTripBeyondNinetyDegrees) {
  const Camera camera =
      MakeCamera(CameraModel::kOpenCVFisheye, {300, 300, 320, 240, 0.01, -0.002, 0.0, 0.0});
  const Eigen::Vector3d direction = Eigen::Vector3d(1.0, 0.3, -0.4).normalized();
  const Eigen::Vector2d pixel = ProjectToPixel(camera, 5.0 * direction);
  ASSERT_TRUE(pixel.allFinite());
  EXPECT_LT(AngleBetween(PixelToBearing(camera, pixel), direction), 1e-9);
}

TEST(CameraProjection, PixelBeyondTheDistortionFoldHasNoBearing) {
  // r_d = r (1 - 0.5 r^2) peaks at r_d = 0.544; a pixel at r_d = 0.8 has no preimage.
  const Camera camera = MakeCamera(CameraModel::kSimpleRadial, {500, 320, 240, -0.5});
  EXPECT_FALSE(PixelToBearing(camera, Eigen::Vector2d(320 + 400, 240)).allFinite());
  EXPECT_TRUE(PixelToBearing(camera, Eigen::Vector2d(320 + 200, 240)).allFinite());
}

TEST(CameraProjection, MeanFocalLength) {
  EXPECT_DOUBLE_EQ(MeanFocalLength(MakeCamera(CameraModel::kPinhole, {500, 520, 320, 240})), 510);
  EXPECT_DOUBLE_EQ(MeanFocalLength(MakeCamera(CameraModel::kRadial, {450, 320, 240, 0, 0})), 450);
}

TEST(CameraProjection, BadParamsAreRejected) {
  EXPECT_THROW(CheckCameraParams(MakeCamera(CameraModel::kPinhole, {500, 500, 320}), "db"),
               InputError);
  EXPECT_THROW(CheckCameraParams(MakeCamera(CameraModel::kOpenCV, {500, 500, 320, 240}), "db"),
               InputError);
  EXPECT_THROW(CheckCameraParams(MakeCamera(CameraModel::kPinhole, {500, 0, 320, 240}), "db"),
               InputError);
  EXPECT_THROW(CheckCameraParams(MakeCamera(CameraModel::kSimplePinhole, {-5, 320, 240}), "db"),
               InputError);
  EXPECT_THROW(CheckCameraParams(MakeCamera(CameraModel::kRadial, {500, 320, 240, NAN, 0.0}), "db"),
               InputError);
  EXPECT_THROW(
      CheckCameraParams(MakeCamera(CameraModel::kPinhole, {INFINITY, 500, 320, 240}), "db"),
      InputError);
  try {
    CheckCameraParams(MakeCamera(CameraModel::kPinhole, {500, 500, 320}), "cameras.txt");
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.source(), "cameras.txt");
    EXPECT_NE(std::string(error.what()).find("PINHOLE"), std::string::npos);
  }
}

}  // namespace
}  // namespace ramap
