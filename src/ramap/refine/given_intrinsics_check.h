// Whether the data prove given intrinsics wrong. Bundle adjustment keeps the focal length and
// principal point of a camera the database marks known (BundleAdjustmentOptions::
// keep_prior_intrinsics). Before it (mapper/refinement.cc), from the poses the model has, a subset
// of the points is adjusted, each group of identical cameras sharing one set of intrinsics:
//   1. the given intrinsics held: the control, so that both steps are measured on the same
//      subset, adjusted alike;
//   2. the focal length freed, and radial distortion added to a camera given without any
//      (SIMPLE_PINHOLE, PINHOLE become SIMPLE_RADIAL, or OPENCV where fx != fy).
// Unless step 2 lowers the group's reprojection RMSE (each error capped at BA's
// max_reprojection_error_px) by a clear margin, nothing changes: a true
// calibration leaves nothing to gain beyond fitting the noise. When it does, and the freed focal
// length stays near the given one, the gain was the lens's: the distortion is kept with the given
// focal length. When the focal length moved further, the data prove it wrong, and
//   3. the focal length alone is freed, to keep the distortion only where it adds a clear margin.
// The margin and the tolerance lie between what the real sets show. Given their true
// calibrations, one camera per image, step 2 gains far less than the margin on Herz-Jesus-P8,
// fountain-P11 and templeRing, and more on kitti07_first160 (rectified, yet radially distorted),
// whose freed focal length stays within the tolerance, so k1 is kept with it. A focal length 5%
// or 10% off gains well beyond the margin on Herz-Jesus-P8 and fountain-P11, but not on
// templeRing, a turntable that leaves the focal length undetermined (BENCHMARKS.md, "A calibration
// the user gives, one camera per image").
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "ramap/refine/bundle_adjustment.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct GivenIntrinsicsTestOptions {
  // Test the given intrinsics at all (--BundleAdjustment.given_intrinsics_test).
  bool enable = true;
  // Step 2 counts when it lowers its cameras' RMSE by at least this fraction; so does the
  // distortion on top of a wrong focal length in step 3.
  double min_rmse_decrease = 0.05;
  // A focal length freed in step 2 that stays within this fraction of the given one confirms it.
  double focal_tolerance = 0.02;
  // Points adjusted in each step (the longest tracks; 0: all).
  int num_points = 2000;
  // Images the steps adjust at most: the middle run of this many image ids (0: all). Each image
  // keeps 50 observations in the steps, so without a bound a long drive tested on nearly every
  // point, as long as its whole bundle adjustment (BENCHMARKS.md, "Scale").
  int max_num_images = 300;

  void Check() const;
};

// Its options (--BundleAdjustment.*), each declared once with its range and help
// (util/option_table.h): the command line, Check(), summary.json and Python read them.
const OptionTable<GivenIntrinsicsTestOptions>& GivenIntrinsicsTestOptionTable();

// One group of cameras sharing intrinsics whose focal length was given.
struct GivenIntrinsicsTest {
  std::vector<uint32_t> camera_ids;
  int num_images = 0;
  int num_observations = 0;
  std::string given_model;
  double given_focal_px = 0.0;  // mean focal length, as given
  double held_rmse_px = 0.0;    // step 1
  // Step 2: radial distortion added (a camera given without any), the focal length freed.
  bool distortion_tried = false;
  double freed_focal_px = 0.0;
  double freed_rmse_px = 0.0;
  // Step 3 (0 when not run): the focal length freed alone.
  double focal_only_rmse_px = 0.0;
  bool distortion_accepted = false;
  bool focal_accepted = false;
  std::string final_model;  // given_model unless the distortion was accepted
};

struct GivenIntrinsicsTestSummary {
  std::vector<GivenIntrinsicsTest> groups;
  double seconds = 0.0;
  // Whether the model's images took the poses of the test's subset (TestGivenIntrinsics).
  bool poses_adjusted = false;
};

// Whether some test changed the intrinsics of its cameras.
bool ChangesIntrinsics(const GivenIntrinsicsTest& test);
// The cameras whose given focal length `test` proved wrong.
std::set<uint32_t> DisprovedCameras(const GivenIntrinsicsTestSummary& test);

// Tests each group of `reconstruction`'s cameras whose focal length `ba` held because it was
// given. The cameras of the groups whose tests passed take the tested model and intrinsics, which
// a following adjustment holds (focal length and principal point) in turn. Where the subset held
// every image, the images take the poses the subset was adjusted to, under the intrinsics kept
// (or nearly: a distortion kept with the given focal length was adjusted with the freed one); the
// points do not change, so they no longer fit those poses until triangulated again. `bearings` and
// `focal_lengths_px` as for BundleAdjust.
// Whether TestGivenIntrinsics has a camera of `reconstruction` to test: the test is enabled and
// BA would hold some given camera whose focal length or distortion it could otherwise refine.
bool TestsSomeCamera(const BundleAdjustmentOptions& ba, const GivenIntrinsicsTestOptions& options,
                     const Reconstruction& reconstruction);

GivenIntrinsicsTestSummary TestGivenIntrinsics(const KeypointBearings& bearings,
                                               const std::map<uint32_t, double>& focal_lengths_px,
                                               const BundleAdjustmentOptions& ba,
                                               const GivenIntrinsicsTestOptions& options,
                                               Reconstruction* reconstruction);

}  // namespace ramap
