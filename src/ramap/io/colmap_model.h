// Reading and writing COLMAP 3.8 sparse models: cameras, images, points3D as .bin or .txt.
#pragma once

#include <string>

#include "ramap/scene/reconstruction.h"

namespace ramap {

enum class ModelFormat { kBinary, kText };

// Reads the model in folder `path`: binary when cameras.bin exists, else text. Throws InputError
// naming the file and the item on any defect (truncated file, unknown camera, NaN pose, a track
// that names a missing image or point2D).
Reconstruction ReadColmapModel(const std::string& path);
Reconstruction ReadColmapModelBinary(const std::string& path);
Reconstruction ReadColmapModelText(const std::string& path);

// Writes the model into folder `path` (created; its three files are replaced), staging each file
// and renaming it into place when complete. Ids are written in increasing order, so writing what
// was read gives identical binary files.
void WriteColmapModel(const Reconstruction& reconstruction, const std::string& path,
                      ModelFormat format = ModelFormat::kBinary);

}  // namespace ramap
