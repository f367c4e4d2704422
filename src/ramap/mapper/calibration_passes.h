// Self-calibration across two passes of the mapper. Cameras whose focal length the database does
// not know are first estimated from the view graph (estimators/view_graph_calibration.h); when
// bundle adjustment then moves a focal length far (MapperOptions::
// max_focal_change_in_bundle_adjustment), or the view graph could not estimate it (a calibration
// pass), the whole pipeline runs a second time through the intrinsics BA found.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <vector>

#include "ramap/estimators/view_graph_calibration.h"
#include "ramap/mapper/mapper_options.h"
#include "ramap/mapper/mapper_summary.h"
#include "ramap/mapper/stage_log.h"
#include "ramap/scene/features.h"
#include "ramap/scene/reconstruction.h"

namespace ramap {

// The view-graph calibration's progress line (each unknown camera's guess and estimate) and time,
// into `report`.
void LogViewGraphCalibration(const ViewGraphCalibrationSummary& calibration, std::ostream* progress,
                             StageReport* report);

// The bundle adjustment options of a subset's adjustment: at most calibration_num_points points
// (the longest tracks), each image keeping at least 50 of its observations.
BundleAdjustmentOptions SubsetAdjustmentOptions(const MapperOptions& options);

struct FirstPass {
  MapperOptions options;
  // The view graph left some camera's focal length unknown: the pass is kept for its intrinsics
  // alone, since a second pass follows.
  bool calibration_pass = false;
};

// The options of the first pass. A calibration pass's relative poses, translation averaging and
// BA on a subset work on the smaller budgets of calibration_pass_num_tracks.
FirstPass FirstPassOptions(const MapperOptions& options,
                           const ViewGraphCalibrationSummary& calibration);

// The largest relative change of a focal length between the intrinsics averaging used (the view
// graph's estimate where it made one, else the database's) and those bundle adjustment wrote into
// `reconstructions` (largest first), over their cameras but the `disproved` ones, whose given
// focal length the test proved wrong; `refined` receives the written cameras.
double FocalChangeInBundleAdjustment(const FeatureDatabase& database,
                                     const ViewGraphCalibrationSummary& calibration,
                                     const std::set<uint32_t>& disproved,
                                     const std::vector<Reconstruction>& reconstructions,
                                     std::map<uint32_t, Camera>* refined);

// The options of the second pass: the intrinsics start where BA left them, so the ordinary
// tolerance suffices: it takes far fewer iterations than the tight one at the same accuracy.
MapperOptions SecondPassOptions(const MapperOptions& options);

// One summary for both passes in `second`: the first pass's view-graph estimates, both passes'
// stage times.
void MergePassSummaries(const MapperSummary& first, MapperSummary* second);

}  // namespace ramap
