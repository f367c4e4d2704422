// What the mapper's stages share while they reconstruct the components of one pass: the input,
// the options, the view graph and where each stage reports.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ramap/pipeline/bearings.h"
#include "ramap/pipeline/stage_log.h"
#include "ramap/scene/camera.h"
#include "ramap/scene/features.h"
#include "ramap/scene/pose_prior.h"
#include "ramap/scene/view_graph.h"

namespace ramap {

// Included by the stages' headers, which MapperOptions includes in turn: declared only.
struct MapperOptions;
struct MapperSummary;
struct MapperComponentSummary;

struct MapperContext {
  const FeatureDatabase& database;
  const MapperOptions& options;
  // The intrinsics the stages use: the database's, with view-graph estimates where it had none.
  const std::map<uint32_t, Camera>& cameras;
  const ImageBearings& bearings;
  const std::vector<ImagePair>& pairs;  // the view graph (stage 1)
  const std::vector<uint32_t>& order;   // image ids in capture order
  bool sequential;
  StageLog& log;
  MapperSummary& summary;
  // Why each image is not (yet) in a model; the stages overwrite it as they go.
  std::map<uint32_t, std::string>& image_reasons;
  const PosePriors& priors;
};

// "NAME1 NAME2", as summaries name an edge.
std::string PairName(const FeatureDatabase& database, uint32_t image_id1, uint32_t image_id2);

}  // namespace ramap
