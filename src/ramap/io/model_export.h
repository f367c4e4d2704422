// A COLMAP model exported for the tools that read other formats (`ramap model_converter
// --output_type PLY|NERFSTUDIO|TUM`): point-cloud viewers, nerfstudio and Gaussian-splatting
// trainers, trajectory evaluators. Each export checks the whole model first and writes nothing
// when it cannot express it.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "ramap/scene/reconstruction.h"

namespace ramap {

enum class ExportFormat { kPly, kNerfstudio, kTum };

// PLY, NERFSTUDIO or TUM (any case); InputError naming `option` otherwise.
ExportFormat ExportFormatFromName(const std::string& name, const std::string& option);

// The points as a binary little-endian PLY (x y z as float, red green blue as uchar); with
// `with_cameras`, each registered image's centre follows as one more vertex, coloured red.
// `source` names the model in errors: one with no point (and no camera asked for) is refused.
void WritePointCloudPly(const Reconstruction& model, const std::string& path, bool with_cameras,
                        const std::string& source);

// nerfstudio's transforms.json for `model`, as its COLMAP converter (ns-process-data's
// colmap_to_json with its defaults) writes it: one shared camera's intrinsics at the top when the
// model's only camera has id 1, else each frame's own; each frame's camera-to-world matrix in
// OpenGL axes (y up, z backwards) in a world turned z-up (applied_transform); frames in image-id
// order, as images/NAME. InputError naming `source` for a model without images, a pose that is
// not finite, or a camera model nerfstudio cannot express (FULL_OPENCV, FOV, THIN_PRISM_FISHEYE).
nlohmann::json NerfstudioTransforms(const Reconstruction& model, const std::string& source);

// The registered images' trajectory as io/trajectory.h writes it (TUM); InputError naming
// `source` for a model without images or with a pose that is not finite.
void WriteTumExport(const Reconstruction& model, const std::string& path,
                    const std::string& source);

// transforms.json and the points, in the same turned world, as sparse_pc.ply, into `folder`
// (created when missing; neither file may exist in it yet).
void WriteNerfstudioExport(const Reconstruction& model, const std::string& folder,
                           const std::string& source);

}  // namespace ramap
