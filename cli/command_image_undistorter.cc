// `ramap image_undistorter --image_path DIR --input_path MODEL --output_path OUT`: COLMAP's
// command with its option names, --output_type COLMAP: OUT/images (undistorted) and OUT/sparse
// (PINHOLE cameras), the layout 3D Gaussian Splatting's convert.py and gsplat read.
#include <iomanip>
#include <iostream>

#include "options.h"
#include "ramap/io/colmap_model.h"
#include "ramap/pipeline/image_undistortion.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"

namespace ramap::cli {

int RunImageUndistorter(int argc, char** argv) {
  CLI::App app("Undistorted images and PINHOLE model in COLMAP's layout (images/, sparse/)",
               "ramap image_undistorter");
  std::string image_path, input_path, output_path, output_type = "COLMAP";
  UndistortionOptions options;
  int num_threads = 2;
  app.add_option("--image_path", image_path, "folder of the model's images")->required();
  app.add_option("--input_path", input_path, "COLMAP model folder (.bin or .txt)")->required();
  app.add_option("--output_path", output_path, "folder for images/ and sparse/")->required();
  app.add_option("--output_type", output_type, "COLMAP (the one layout ramap writes)")
      ->capture_default_str();
  app.add_option("--blank_pixels", options.blank_pixels,
                 "share of blank border pixels allowed, 0 (crop) to 1 (keep every pixel)")
      ->capture_default_str();
  app.add_option("--min_scale", options.min_scale)->capture_default_str();
  app.add_option("--max_scale", options.max_scale)->capture_default_str();
  app.add_option("--max_image_size", options.max_image_size, "longest side (-1: as the images)")
      ->capture_default_str();
  app.add_option("--num_threads", num_threads)->capture_default_str()->check(AtLeast(1, 256));
  if (const std::optional<int> code = ParseOptions(app, argc, argv)) return *code;
  if (output_type != "COLMAP") {
    throw InputError("--output_type", "'" + output_type +
                                          "': ramap writes COLMAP's layout only (PMVS and "
                                          "CMP-MVS are not supported)");
  }
  options.Check();
  CheckFolderOutput("--output_path", output_path, {input_path});

  const Reconstruction model = ReadColmapModel(input_path);
  const ImageUndistortionSummary summary = UndistortImages(
      model, image_path, output_path, options, ModelFormat::kBinary, num_threads, &std::cout);
  std::cout << std::fixed << std::setprecision(2)
            << "ramap image_undistorter: " << summary.num_images << " images undistorted to "
            << model.cameras.size() << " PINHOLE camera(s), " << summary.seconds << " s -> "
            << output_path << "/images, " << output_path << "/sparse\n";
  return 0;
}

}  // namespace ramap::cli
