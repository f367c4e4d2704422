// Prior alignment: the averaged model, known up to a similarity, mapped onto the pose priors
// (GPS) of its images by a robust similarity fit over camera centres (RANSAC over triples, then a
// least-squares refit on the inliers: geometry/alignment.h). Fixes whose aligned error exceeds the
// threshold are reported as outliers by image, and left out of every later use of the priors.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ramap/averaging/translation_averaging.h"
#include "ramap/geometry/alignment.h"
#include "ramap/scene/pose_prior.h"
#include "ramap/scene/reconstruction.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct PriorAlignmentOptions {
  // Fit the model to the priors and write it in their frame. The two uses below need the fit:
  // without it they are ignored.
  bool align = true;
  // Priors as rows of translation averaging (after a first fit), so GPS bounds scale drift.
  bool use_in_translation_averaging = true;
  // Priors as residuals of the optional bundle adjustment.
  bool use_in_bundle_adjustment = true;
  // RANSAC inlier threshold on the aligned centre distance (m); 0: three times the median 3D
  // standard deviation of the priors (3 sigma; with the default 3, 3, 6 m: 22 m).
  double max_alignment_error_m = 0.0;
  // Inliers needed to accept a fit (three non-collinear centres fix a similarity; more make a
  // wrong fix unlikely).
  int min_num_inliers = 4;
  // Largest rotation uncertainty of the fit, about sigma / (spread * sqrt(N)) radians for N priors
  // of 3D deviation sigma spread over `spread` (RMS distance from their centroid). A turntable
  // scan two metres across tagged by a 5 m GPS (30 images: ~25 deg) would take its rotation and
  // scale from the noise, so it is left unregistered, with the reason; KITTI 07's 160 fixes at the
  // default deviations over its 28.5 m: ~1.2 deg.
  double max_fit_uncertainty_deg = 5.0;

  void Check() const;
};

// Its options (--PosePrior.*), each declared once with its range and help (util/option_table.h):
// the command line, Check(), summary.json and Python read them.
const OptionTable<PriorAlignmentOptions>& PriorAlignmentOptionTable();

struct PriorOutlier {
  uint32_t image_id = 0;
  double error_m = 0.0;  // distance of the aligned centre from its prior
};

struct PriorAlignmentSummary {
  bool aligned = false;
  std::string problem;  // why not, when not aligned to its priors
  int num_priors = 0;   // registered images with a prior
  int num_inliers = 0;
  double rmse_m = 0.0;  // aligned centre vs prior, over the inliers
  double threshold_m = 0.0;
  double scale = 0.0;  // metres per unit of the model before prior alignment
  bool used_in_translation_averaging = false;
  bool used_in_bundle_adjustment = false;
  std::vector<PriorOutlier> outliers;  // largest error first
};

struct PriorAlignment {
  PriorAlignmentSummary summary;
  Sim3d prior_from_model;
  std::map<uint32_t, PosePrior> inliers;  // the priors the fit accepted
};

// Robustly fits prior_from_model to the priors of the images in `centers` (model frame). On
// failure (too few priors, all identical or on one line, no consensus) summary.problem says why.
PriorAlignment AlignCentersToPriors(const std::map<uint32_t, Eigen::Vector3d>& centers,
                                    const PosePriors& priors, const PriorAlignmentOptions& options);

// The inlier priors of `alignment` as translation averaging rows in the model frame: the prior
// mapped back through the fit, its information scaled and rotated with it.
std::vector<PosePriorInModel> PriorsInModelFrame(const PriorAlignment& alignment);

// Recomputes summary.rmse_m and the outliers' errors from the final camera centres of a
// `reconstruction` aligned to its priors (after bundle adjustment moved them).
void MeasurePriorErrors(const Reconstruction& reconstruction, const PosePriors& priors,
                        const std::map<uint32_t, PosePrior>& inliers,
                        PriorAlignmentSummary* summary);

// Every pose and point mapped by `new_from_old`.
// Fits `model`'s camera centres to `priors` (AlignCentersToPriors) and, when that succeeds, moves
// the model into the priors' frame (`ramap model_aligner`).
PriorAlignment AlignModelToPriors(const PosePriors& priors, const PriorAlignmentOptions& options,
                                  Reconstruction* model);

void TransformReconstruction(const Sim3d& new_from_old, Reconstruction* reconstruction);

}  // namespace ramap
