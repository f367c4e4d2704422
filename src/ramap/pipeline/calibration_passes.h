// Self-calibration across two passes of the mapper. Cameras whose focal length the database does
// not know are first estimated from the view graph (pipeline/view_graph_calibration.h); when
// bundle adjustment then moves a focal length far (MapperOptions::
// max_focal_change_in_bundle_adjustment), or the view graph could not estimate it (a calibration
// pass), the whole pipeline runs a second time through the intrinsics BA found.
#pragma once

#include <cstdint>
#include <map>

#include "ramap/pipeline/mapper.h"
#include "ramap/pipeline/stage_log.h"

namespace ramap {

// One progress line for the view-graph calibration: each unknown camera's guess and estimate.
void LogViewGraphCalibration(const ViewGraphCalibrationSummary& calibration, StageLog* log);

// The bundle adjustment options of a subset's adjustment: at most calibration_num_points points
// (the longest tracks), each image keeping at least 50 of its observations.
BundleAdjustmentOptions SubsetAdjustmentOptions(const MapperOptions& options);

// The options of the first pass. When the view graph left some camera's focal length unknown, it
// is a calibration pass (summary->calibration_pass set), kept for its intrinsics alone since a
// second pass follows: its relative poses, translation averaging and BA on a subset work on the
// smaller budgets of calibration_pass_num_tracks.
MapperOptions FirstPassOptions(const MapperOptions& options,
                               const ViewGraphCalibrationSummary& calibration,
                               MapperSummary* summary);

// The largest relative change of a focal length between the intrinsics averaging used and those
// bundle adjustment wrote, over the cameras of the models but those whose given focal length the
// test proved wrong; `refined` receives those cameras.
double FocalChangeInBundleAdjustment(const MapperResult& result,
                                     std::map<uint32_t, Camera>* refined);

// The options of the second pass: the intrinsics start where BA left them, so the ordinary
// tolerance suffices: it takes far fewer iterations than the tight one at the same accuracy.
MapperOptions SecondPassOptions(const MapperOptions& options);

// One summary for both passes in `second`: the first pass's view-graph estimates, both passes'
// stage times.
void MergePassSummaries(const MapperSummary& first, MapperSummary* second);

}  // namespace ramap
