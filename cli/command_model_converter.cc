// `ramap model_converter`: converts a COLMAP sparse model between the binary and text formats,
// with COLMAP's option names. The input is read and checked whole before any output appears.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <iostream>
#include <string>

#include "options.h"
#include "ramap/io/colmap_model.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"

namespace ramap::cli {

int RunModelConverter(int argc, char** argv) {
  CLI::App app("Convert a COLMAP sparse model between .bin and .txt", "ramap model_converter");
  std::string input_path;
  std::string output_path;
  std::string output_type;
  app.add_option("--input_path", input_path, "Folder of the model to read (.bin or .txt)")
      ->required();
  app.add_option("--output_path", output_path, "Folder to write (created)")->required();
  app.add_option("--output_type", output_type, "BIN or TXT")->required();
  if (const std::optional<int> code = ParseOptions(app, argc, argv)) return *code;

  const ModelFormat format = ModelFormatFromName(output_type, "--output_type");
  CheckFolderOutput("--output_path", output_path, {input_path});
  const Reconstruction model = ReadColmapModel(input_path);
  WriteColmapModel(model, output_path, format);
  std::cout << "Wrote " << model.cameras.size() << " cameras, " << model.images.size()
            << " images, " << model.points3D.size() << " points to " << output_path << " ("
            << (format == ModelFormat::kBinary ? "BIN" : "TXT") << ")\n";
  return 0;
}

}  // namespace ramap::cli
