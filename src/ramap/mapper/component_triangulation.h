// Stage 5 of the mapper on one component: every track triangulated with the poses fixed
// (estimators/track_triangulation.h), and the images its points leave out placed again from them
// (estimators/reregistration.h).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ramap/estimators/track_triangulation.h"
#include "ramap/mapper/mapper_state.h"

namespace ramap {

// Every track of `tracks` triangulated with `poses` fixed, through `bearings` and `cameras` (the
// refined ones after bundle adjustment), the cameras written into the model, under `options` (the
// mapper's, or those of a BA's start); the component's triangulation figures and the stage's line
// (`what` opens its message) into `state`.
Reconstruction TriangulateComponent(const PassInput& input,
                                    const std::map<uint32_t, Rigid3d>& poses,
                                    const std::vector<Track>& tracks, const ImageBearings& bearings,
                                    const std::map<uint32_t, Camera>& cameras,
                                    const std::string& what,
                                    const TrackTriangulationOptions& options,
                                    ComponentState* state);

// The averaged poses (in the priors' frame when aligned to them) into state.poses, and every track
// triangulated with them into state.model, under the looser bound of a BA's start when BA follows.
ComponentState TriangulateAveragedPoses(const PassInput& input, ComponentState state);

// The images the points leave out, tried again from them (ReregistrationOptions); the tracks
// triangulated again when some pose changed.
ComponentState ReregisterComponent(const PassInput& input, ComponentState state);

}  // namespace ramap
