// The mapper's state. A pass reads its input (PassInput) and never writes it; each component of
// the view graph is carried from its edges to its model by one ComponentState, which every stage
// takes and returns with what it made and what it reports (mapper/stage_log.h). The summary is
// written from the states once every component is done (mapper/mapper.cc), never read back.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <future>
#include <map>
#include <optional>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "ramap/averaging/pair_directions.h"
#include "ramap/averaging/rotation_averaging.h"
#include "ramap/averaging/translation_averaging.h"
#include "ramap/estimators/bearings.h"
#include "ramap/estimators/prior_alignment.h"
#include "ramap/graph/tracks.h"
#include "ramap/mapper/mapper_options.h"
#include "ramap/mapper/mapper_summary.h"
#include "ramap/mapper/stage_log.h"
#include "ramap/scene/camera.h"
#include "ramap/scene/features.h"
#include "ramap/scene/pose_prior.h"
#include "ramap/scene/reconstruction.h"
#include "ramap/scene/view_graph.h"

namespace ramap {

// What every stage of one pass reads: the input, and what the pass made before it cut the view
// graph into components.
struct PassInput {
  const FeatureDatabase& database;
  const MapperOptions& options;  // this pass's (mapper/calibration_passes.h)
  // The intrinsics the stages use: the database's, with view-graph estimates where it had none.
  const std::map<uint32_t, Camera>& cameras;
  const ImageBearings& bearings;        // through `cameras`
  const std::vector<ImagePair>& pairs;  // the view graph
  const std::vector<uint32_t>& order;   // image ids in capture order
  bool sequential = false;
  const PosePriors& priors;
  // The pass only finds intrinsics for the next one: its bundle adjustment ends once they settle.
  bool calibration_pass = false;
  std::ostream* progress = nullptr;  // one line per stage; nullptr: none
};

// The tracks of a whole component, built before its rotations are averaged: rotation averaging
// runs mostly on one thread (a second one barely speeds it), and leaves the other core to them.
// They are the tracks translation averaging needs when rotation averaging keeps every edge, the
// common case, which makes a long drive's translation stage quicker (BENCHMARKS.md, "Scale");
// otherwise translation averaging builds them again over the edges it kept.
struct EarlyTracks {
  std::set<uint64_t> pair_ids;  // the edges they are built over
  std::future<std::vector<Track>> built;
};

// What translation averaging made of a component.
struct ComponentTranslations {
  std::vector<PairDirection> directions;
  std::vector<Track> tracks;  // feature tracks over the kept pairs (triangulated later)
  TranslationAveragingResult positions;
  // Kept pure-rotation edges, both ways: they place the images nothing else positions.
  std::multimap<uint32_t, uint32_t> pure_rotation_neighbours;
  bool tracks_built_early = false;  // the EarlyTracks fitted what rotation averaging kept
};

// One connected component on its way from the view graph to a model, in the order the stages
// fill it in.
struct ComponentState {
  RotationGraph graph;  // the component's accepted pairs, as rotation averaging reads them
  EarlyTracks early_tracks;
  // Rotation averaging: each estimated image's rotation (cam_from_world), each edge's status.
  std::map<uint32_t, Eigen::Quaterniond> rotations;
  std::vector<EdgeStatus> edge_status;
  // Translation averaging; none when it failed, which ends the component (its images' reasons
  // say why).
  std::optional<ComponentTranslations> translations;
  PriorAlignment prior_alignment;  // aligned false without priors
  // cam_from_world of each placed image, in the priors' frame when aligned to them.
  std::map<uint32_t, Rigid3d> poses;
  Reconstruction model;
  // Given cameras whose focal length the test of the given intrinsics proved wrong.
  std::set<uint32_t> disproved_cameras;
  MapperComponentSummary summary;
  StageReport report;
  // The component has its model; what the stages worked on is released once it is done.
  bool made = false;
};

// "NAME1 NAME2", as summaries name an edge.
std::string PairName(const FeatureDatabase& database, uint32_t image_id1, uint32_t image_id2);

// Records a stage of `state`'s component: its time and progress line, into its report.
void RecordStage(const PassInput& input, const std::string& stage, double seconds,
                 const std::string& message, ComponentState* state);

}  // namespace ramap
