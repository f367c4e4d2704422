#include <string>
#include <utility>
#include <vector>

#include "ramap/features/image_reader.h"

namespace ramap {

namespace {

using Table = OptionTable<ImageReaderOptions>;

void Declare(Table& t) {
  t.push_back(
      AlsoChecked(TextOption<ImageReaderOptions>(
                      "ImageReader.camera_model", [](auto& o) -> auto& { return o.camera_model; },
                      "COLMAP camera model"),
                  [](const std::string& text) -> std::string {
                    return CameraModelFromName(text) ? "" : "unknown camera model '" + text + "'";
                  }));
  t.push_back(TextOption<ImageReaderOptions>(
      "ImageReader.camera_params", [](auto& o) -> auto& { return o.camera_params; },
      "known intrinsics at full resolution, e.g. fx,fy,cx,cy for PINHOLE (empty: EXIF or the "
      "default focal length)"));
  t.push_back(BoolOption<ImageReaderOptions>(
      "ImageReader.single_camera", [](auto& o) -> auto& { return o.single_camera; },
      "1: one camera for all images"));
  t.push_back(NumberOption<ImageReaderOptions>(
      "ImageReader.default_focal_length_factor",
      [](auto& o) -> auto& { return o.default_focal_length_factor; }, Above(0),
      "focal length guess, times the longest side, without camera_params"));
  t.push_back(ColmapNamed(
      NumberOption<ImageReaderOptions>(
          "FeatureExtraction.num_threads", [](auto& o) -> auto& { return o.num_threads; },
          AtLeast(1, 256), "images read and described at once"),
      {"SiftExtraction.num_threads"}));
}

}  // namespace

const OptionTable<ImageReaderOptions>& ImageReaderOptionTable() {
  static const Table table = [] {
    Table t;
    Declare(t);
    return t;
  }();
  return table;
}

}  // namespace ramap
