#include "ramap/scene/reconstruction.h"

namespace ramap {

Reconstruction ModelOfPoses(const std::map<std::string, Rigid3d>& cam_from_world,
                            const Camera& camera) {
  Reconstruction model;
  model.cameras[1] = camera;
  model.cameras[1].camera_id = 1;
  uint32_t image_id = 1;
  for (const auto& [name, pose] : cam_from_world) {
    Image image;
    image.image_id = image_id;
    image.name = name;
    image.camera_id = 1;
    image.cam_from_world = pose;
    model.images[image_id++] = image;
  }
  return model;
}

}  // namespace ramap
