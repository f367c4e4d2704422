// `ramap model_converter`: converts a COLMAP sparse model between the binary and text formats,
// with COLMAP's option names, or exports it for other tools (PLY points, nerfstudio's
// transforms.json, a TUM trajectory). The input is read and checked whole before any output
// appears.
#include <CLI/CLI.hpp>
#include <cctype>
#include <iostream>
#include <string>

#include "options.h"
#include "ramap/io/colmap_model.h"
#include "ramap/io/model_export.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"

namespace ramap::cli {
namespace {

// The output is checked before the model is read.
void CheckExportOutput(ExportFormat format, const std::string& input_path,
                       const std::string& output_path, bool export_cameras) {
  if (export_cameras && format != ExportFormat::kPly) {
    throw InputError("--export_cameras", "applies to --output_type PLY only");
  }
  if (format == ExportFormat::kNerfstudio) {
    CheckFolderOutput("--output_path", output_path, {input_path});
  } else {
    CheckFileOutput("--output_path", output_path, {input_path});
  }
}

void Export(const Reconstruction& model, ExportFormat format, const std::string& input_path,
            const std::string& output_path, bool export_cameras) {
  switch (format) {
    case ExportFormat::kPly:
      WritePointCloudPly(model, output_path, export_cameras, input_path);
      std::cout << "Wrote the points" << (export_cameras ? " and camera centres" : "") << " of "
                << input_path << " to " << output_path << " (PLY)\n";
      return;
    case ExportFormat::kNerfstudio:
      WriteNerfstudioExport(model, output_path, input_path);
      std::cout << "Wrote " << output_path << "/transforms.json (" << model.images.size()
                << " frames) and " << output_path << "/sparse_pc.ply (NERFSTUDIO)\n";
      return;
    case ExportFormat::kTum:
      WriteTumExport(model, output_path, input_path);
      std::cout << "Wrote the trajectory of " << model.images.size() << " images to " << output_path
                << " (TUM)\n";
      return;
  }
}

struct ModelConverterCommand {
  std::string input_path, output_path, output_type;
  bool export_cameras = false;
};

const OptionTable<ModelConverterCommand>& ModelConverterCommandTable() {
  static const OptionTable<ModelConverterCommand> table = {
      Required(PathOption<ModelConverterCommand>(
          "input_path", [](auto& o) -> auto& { return o.input_path; },
          "folder of the model to read (.bin or .txt)")),
      Required(PathOption<ModelConverterCommand>(
          "output_path", [](auto& o) -> auto& { return o.output_path; },
          "BIN, TXT, NERFSTUDIO: folder to write (created); PLY, TUM: file to write")),
      Required(AlsoChecked(
          TextOption<ModelConverterCommand>(
              "output_type", [](auto& o) -> auto& { return o.output_type; },
              "BIN or TXT (COLMAP model), PLY (points), NERFSTUDIO (transforms.json and "
              "sparse_pc.ply), TUM (trajectory)"),
          [](const std::string& text) -> std::string {
            try {
              ModelFormatFromName(text, "--output_type");
            } catch (const InputError&) {
              try {
                ExportFormatFromName(text, "--output_type");
              } catch (const InputError&) {
                return "'" + text + "' is not BIN, TXT, PLY, NERFSTUDIO or TUM";
              }
            }
            return "";
          })),
      BoolOption<ModelConverterCommand>(
          "export_cameras", [](auto& o) -> auto& { return o.export_cameras; },
          "PLY: add each camera centre, in red")};
  return table;
}

}  // namespace

std::string ModelConverterOptionsMarkdown() {
  return OptionTableMarkdown(ModelConverterCommandTable(), ModelConverterCommand());
}

int RunModelConverter(int argc, char** argv) {
  CLI::App app("Convert a COLMAP sparse model between .bin and .txt, or export it",
               "ramap model_converter");
  ModelConverterCommand command;
  if (const auto code = ParseCommandLine(app, ModelConverterCommandTable(), &command, argc, argv))
    return *code;
  const std::string& input_path = command.input_path;
  const std::string& output_path = command.output_path;
  const std::string& output_type = command.output_type;
  const bool export_cameras = command.export_cameras;

  std::string upper = output_type;
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (upper != "BIN" && upper != "TXT") {
    const ExportFormat format = ExportFormatFromName(output_type, "--output_type");
    CheckExportOutput(format, input_path, output_path, export_cameras);
    Export(ReadColmapModel(input_path), format, input_path, output_path, export_cameras);
    return 0;
  }
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
