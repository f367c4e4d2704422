// Reading and writing COLMAP sparse models: cameras, images, points3D as .bin or .txt (COLMAP 3.8's
// files, which 4.x keeps), and COLMAP 4's rigs and frames beside them (io/colmap_model_rigs.h).
#pragma once

#include <string>

#include "ramap/scene/features.h"
#include "ramap/scene/reconstruction.h"

namespace ramap {

enum class ModelFormat { kBinary, kText };

// "BIN" or "TXT" (any case), as COLMAP's --output_type; throws InputError naming `option` else.
ModelFormat ModelFormatFromName(const std::string& name, const std::string& option);

// Reads the model in folder `path`: binary when cameras.bin exists, else text. Throws InputError
// naming the file and the item on any defect: missing or truncated file ("images.bin: truncated
// while reading image 3 (of 12)"), trailing bytes, unknown camera model, wrong parameter count,
// NaN/inf in a pose, intrinsics, keypoint or 3D point, a quaternion far from unit norm (> 1e-2),
// an image whose camera is missing, a track element naming a missing image or an out-of-range
// point2D, an image point naming a missing 3D point (or one whose track does not list it back),
// duplicate ids, and text lines that do not parse (with the line number).
// Values are kept exactly as stored (COLMAP renormalises quaternions on reading; we do not, so
// that read -> write is bit-identical).
Reconstruction ReadColmapModel(const std::string& path);
Reconstruction ReadColmapModelBinary(const std::string& path);
Reconstruction ReadColmapModelText(const std::string& path);

// Writes the model into folder `path` (created; its five files are replaced: the three of COLMAP
// 3.8, and rigs and frames for COLMAP 4), staging each file
// and renaming it into place when complete. Ids are written in increasing order, so writing what
// was read gives identical binary files; text uses COLMAP 3.8's layout and header comments, with
// 17 significant digits (lossless). The model is checked as by the readers before anything is
// created: a bad model throws InputError and leaves nothing behind. Text cannot hold image names
// with white space (InputError).
// Why an image of this name cannot be written in `format` (empty, NUL, white space in text); empty
// when it can. Commands check their input's names with it before any work starts.
std::string ImageNameProblem(const std::string& name, ModelFormat format);

// Throws InputError naming `source` and the first image of `database` whose name cannot be
// written in `format`; `why_format` (e.g. "--output_type TXT") ends the message.
void CheckImageNamesFit(const FeatureDatabase& database, ModelFormat format,
                        const std::string& source, const std::string& why_format);

void WriteColmapModel(const Reconstruction& reconstruction, const std::string& path,
                      ModelFormat format = ModelFormat::kBinary);

}  // namespace ramap
