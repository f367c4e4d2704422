// A COLMAP 4 model's rigs.bin / frames.bin (and .txt), beside cameras, images and points3D.
//
// COLMAP 3.8 ignores the two files; COLMAP 4 reads them, and takes a frame's pose (rig_from_world,
// and sensor_from_rig for the rig's other cameras) as the pose of its images. ramap keeps each
// image's cam_from_world as the truth, so on writing every frame's pose is derived from its
// images: the model COLMAP 4 reads has exactly the poses of images.bin. Formats as COLMAP 4.1.1's
// src/colmap/scene/reconstruction_io_{binary,text}.cc read them.
#pragma once

#include <ostream>
#include <string>

#include "ramap/scene/reconstruction.h"

namespace ramap {

// Reads rigs.EXT and frames.EXT of `folder` into model->rigs and frames when both are there
// (EXT: "bin" or "txt"); nothing when neither is. Throws InputError naming the file and the item:
// only one of the two files, a truncated or malformed record, an unknown sensor type, a frame of
// an unknown rig, a datum of a sensor its rig does not have, a camera not in the model.
void ReadColmapModelRigs(const std::string& folder, bool binary, Reconstruction* model);

// The rigs and frames to write with `model`: its own when every frame can be written as COLMAP 4
// expects (each frame's registered images include one from which the frame's pose follows: the
// reference camera's, or another camera's with a known sensor_from_rig), with every frame's pose
// and every calibrated sensor_from_rig derived from the images' poses, and only registered images
// listed. Otherwise, and for a model without rigs: one rig per camera (rig id = camera id) and one
// frame per registered image (frame id = image id), as COLMAP 4 makes for a model without them.
struct ModelRigsAndFrames {
  Rigs rigs;
  Frames frames;
};
ModelRigsAndFrames RigsAndFramesToWrite(const Reconstruction& model);

void WriteRigsBinary(const ModelRigsAndFrames& rigs, std::ostream& out);
void WriteFramesBinary(const ModelRigsAndFrames& rigs, std::ostream& out);
void WriteRigsText(const ModelRigsAndFrames& rigs, std::ostream& out);
void WriteFramesText(const ModelRigsAndFrames& rigs, std::ostream& out);

}  // namespace ramap
