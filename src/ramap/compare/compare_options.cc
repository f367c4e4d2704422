#include "ramap/compare/compare_options.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace ramap {

namespace {

// "" when `program` names an executable file: a path, or a name found on PATH.
std::string ExecutableProblem(const std::string& program) {
  const auto executable = [](const std::filesystem::path& path) {
    return std::filesystem::is_regular_file(path) && access(path.c_str(), X_OK) == 0;
  };
  if (program.find('/') != std::string::npos) {
    if (!std::filesystem::exists(program)) return "no such file: " + program;
    return executable(program) ? "" : program + " is not an executable file";
  }
  const char* path = std::getenv("PATH");
  std::istringstream folders(path ? path : "");
  for (std::string folder; std::getline(folders, folder, ':');) {
    if (!folder.empty() && executable(std::filesystem::path(folder) / program)) return "";
  }
  return "no program '" + program + "' on the PATH";
}

template <typename Access>
OptionDeclaration<CompareOptions> Path(std::string name, Access access, std::string help) {
  return TextOption<CompareOptions>(std::move(name), access, std::move(help));
}

template <typename Access>
OptionDeclaration<CompareOptions> Program(std::string name, Access access, std::string help) {
  return AlsoChecked(Path(std::move(name), access, std::move(help)),
                     [](const std::string& text) -> std::string {
                       return text.empty() ? "" : ExecutableProblem(text);
                     });
}

OptionTable<CompareOptions> BuildTable() {
  OptionTable<CompareOptions> t;
  t.push_back(Required(Path(
      "database_path", [](auto& o) -> auto& { return o.database_path; },
      "COLMAP database with verified matches")));
  t.push_back(Required(Path(
      "output_path", [](auto& o) -> auto& { return o.output_path; },
      "folder for the models, logs, report and figures")));
  t.push_back(Path(
      "image_path", [](auto& o) -> auto& { return o.image_path; },
      "the images (colours; COLMAP's mapper wants one)"));
  t.push_back(Path(
      "ground_truth", [](auto& o) -> auto& { return o.ground_truth_path; },
      "ground-truth file or folder"));
  t.push_back(Path(
      "ground_truth_format", [](auto& o) -> auto& { return o.ground_truth_format; },
      "tum, kitti, strecha, middlebury or colmap"));
  t.push_back(Program(
      "colmap_path", [](auto& o) -> auto& { return o.colmap_binary; },
      "the reference colmap binary (3.8)"));
  t.push_back(Program(
      "peer_colmap", [](auto& o) -> auto& { return o.peer_colmap_binary; },
      "a COLMAP 4 binary (scripts/peers.sh): adds its mapper and global_mapper "
      "(GLOMAP), each on a copy of the database"));
  t.push_back(BoolOption<CompareOptions>(
      "Compare.refine_intrinsics", [](auto& o) -> auto& { return o.refine_intrinsics; },
      "0: intrinsics fixed in every mapper (fair with known calibration); 1: refined"));
  t.push_back(NumberOption<CompareOptions>(
      "Compare.num_threads", [](auto& o) -> auto& { return o.num_threads; }, AtLeast(1, 256),
      "threads of every mapper"));
  t.push_back(BoolOption<CompareOptions>(
      "Compare.png_figures", [](auto& o) -> auto& { return o.png_figures; },
      "1: also the figures as PNG files (report.html shows them interactively)"));
  return t;
}

}  // namespace

const OptionTable<CompareOptions>& CompareOptionTable() {
  static const OptionTable<CompareOptions> table = BuildTable();
  return table;
}

}  // namespace ramap
