// `ramap image_undistorter --image_path DIR --input_path MODEL --output_path OUT`: COLMAP's
// command with its option names, --output_type COLMAP: OUT/images (undistorted) and OUT/sparse
// (PINHOLE cameras), the layout 3D Gaussian Splatting's convert.py and gsplat read.
#include <iomanip>
#include <iostream>

#include "options.h"
#include "ramap/io/colmap_model.h"
#include "ramap/jobs/image_undistortion.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"

namespace ramap::cli {
namespace {

struct UndistorterCommand {
  std::string image_path, input_path, output_path, output_type = "COLMAP";
  UndistortionOptions options;
  int num_threads = 2;
};

const OptionTable<UndistorterCommand>& UndistorterCommandTable() {
  static const OptionTable<UndistorterCommand> table = [] {
    OptionTable<UndistorterCommand> t;
    t.push_back(Required(PathOption<UndistorterCommand>(
        "image_path", [](auto& o) -> auto& { return o.image_path; },
        "folder of the model's images")));
    t.push_back(Required(PathOption<UndistorterCommand>(
        "input_path", [](auto& o) -> auto& { return o.input_path; },
        "COLMAP model folder (.bin or .txt)")));
    t.push_back(Required(PathOption<UndistorterCommand>(
        "output_path", [](auto& o) -> auto& { return o.output_path; },
        "folder for images/ and sparse/")));
    t.push_back(AlsoChecked(
        TextOption<UndistorterCommand>(
            "output_type", [](auto& o) -> auto& { return o.output_type; },
            "COLMAP (the one layout ramap writes)"),
        [](const std::string& text) -> std::string {
          return text == "COLMAP" ? ""
                                  : "'" + text +
                                        "': ramap writes COLMAP's layout only (PMVS and CMP-MVS "
                                        "are not supported)";
        }));
    AppendOptions(
        UndistortionOptionTable(), [](auto& o) -> auto& { return o.options; }, &t);
    t.push_back(NumberOption<UndistorterCommand>(
        "num_threads", [](auto& o) -> auto& { return o.num_threads; }, AtLeast(1, 256),
        "images undistorted at once"));
    return t;
  }();
  return table;
}

}  // namespace

std::string ImageUndistorterOptionsMarkdown() {
  return OptionTableMarkdown(UndistorterCommandTable(), UndistorterCommand());
}

int RunImageUndistorter(int argc, char** argv) {
  CLI::App app("Undistorted images and PINHOLE model in COLMAP's layout (images/, sparse/)",
               "ramap image_undistorter");
  UndistorterCommand command;
  if (const auto code = ParseCommandLine(app, UndistorterCommandTable(), &command, argc, argv))
    return *code;
  const std::string& image_path = command.image_path;
  const std::string& input_path = command.input_path;
  const std::string& output_path = command.output_path;
  const UndistortionOptions& options = command.options;
  const int num_threads = command.num_threads;
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
