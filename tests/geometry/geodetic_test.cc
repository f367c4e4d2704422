#include "ramap/geometry/geodetic.h"

#include <gtest/gtest.h>

#include "ramap/util/error.h"

namespace ramap {
namespace {

// Karlsruhe, where KITTI was recorded.
const GeodeticPoint kOrigin{49.011, 8.4165, 115.0};

TEST(Geodetic, Wgs84ToEnuAndBackToTheMillimetre) {
  const LocalEnuFrame frame(kOrigin);
  for (const Eigen::Vector3d enu :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(120.5, -43.25, 3.0),
        Eigen::Vector3d(-5000, 8000, -60), Eigen::Vector3d(40e3, 30e3, 900)}) {
    const GeodeticPoint point = frame.ToGeodetic(enu);
    const Eigen::Vector3d back = frame.FromGeodetic(point);
    EXPECT_LT((back - enu).norm(), 1e-3) << enu.transpose();
    // And through earth-centred coordinates.
    EXPECT_LT((frame.FromEcef(GeodeticToEcef(point)) - enu).norm(), 1e-3);
    EXPECT_LT((frame.ToEcef(enu) - GeodeticToEcef(point)).norm(), 1e-3);
  }
  // One metre north is 1 / 111.2 km of latitude there; east is up-free and north-free.
  const GeodeticPoint north = frame.ToGeodetic({0, 1, 0});
  EXPECT_NEAR((north.latitude_deg - kOrigin.latitude_deg) * 111.2e3, 1.0, 2e-3);
  EXPECT_NEAR(north.longitude_deg, kOrigin.longitude_deg, 1e-12);
  const GeodeticPoint origin = EcefToGeodetic(GeodeticToEcef(kOrigin));
  EXPECT_NEAR(origin.latitude_deg, kOrigin.latitude_deg, 1e-10);
  EXPECT_NEAR(origin.altitude_m, kOrigin.altitude_m, 1e-6);
}

TEST(Geodetic, ParsesAndRejectsOrigins) {
  const GeodeticPoint point = ParseGeodeticPoint("49.011,8.4165,115", "--PosePrior.origin");
  EXPECT_DOUBLE_EQ(point.latitude_deg, 49.011);
  EXPECT_DOUBLE_EQ(point.altitude_m, 115.0);
  for (const char* bad : {"49.011,8.4165", "91,0,0", "a,b,c", "1,2,3,4", "nan,0,0"}) {
    EXPECT_THROW(ParseGeodeticPoint(bad, "--PosePrior.origin"), InputError) << bad;
  }
  EXPECT_FALSE(IsValidGeodeticPoint({10, 500, 0}));
  EXPECT_FALSE(IsValidGeodeticPoint({10, 20, 2e5}));
  EXPECT_TRUE(IsValidGeodeticPoint({-33.9, 151.2, 40}));
}

}  // namespace
}  // namespace ramap
