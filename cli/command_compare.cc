// `ramap compare --database_path DB --output_path DIR [--image_path DIR] [--ground_truth PATH
// --ground_truth_format FORMAT] [--peer_colmap PATH]`: COLMAP's BA mapper, the peers (COLMAP 4's
// incremental mapper and GLOMAP) when given, and ramap's averaging mapper with and without BA, on
// the same database (compare/compare_mappers.h). Writes DIR/report.html, DIR/report.md and
// DIR/report.json.
#include <CLI/CLI.hpp>

#include "options.h"
#include "ramap/compare/compare_mappers.h"

namespace ramap::cli {

int RunCompare(int argc, char** argv) {
  CLI::App app(
      "COLMAP's BA mapper vs ramap's averaging mapper (with and without BA) on one database, with "
      "COLMAP 4 and GLOMAP as peers when given: accuracy, time and figures.",
      "ramap compare");
  CompareOptions options;
  app.add_option("--database_path", options.database_path, "COLMAP database with verified matches")
      ->required();
  app.add_option("--output_path", options.output_path,
                 "folder for the models, logs, report and figures")
      ->required();
  app.add_option("--image_path", options.image_path,
                 "the images (colours; COLMAP's mapper wants one)");
  app.add_option("--ground_truth", options.ground_truth_path, "ground-truth file or folder");
  app.add_option("--ground_truth_format", options.ground_truth_format,
                 "tum, kitti, strecha, middlebury or colmap");
  app.add_option("--colmap_path", options.colmap_binary, "the reference colmap binary (3.8)")
      ->capture_default_str();
  app.add_option(
      "--peer_colmap", options.peer_colmap_binary,
      "a COLMAP 4 binary (scripts/peers.sh): adds its mapper and global_mapper (GLOMAP), "
      "each on a copy of the database");
  app.add_option("--Compare.refine_intrinsics", options.refine_intrinsics,
                 "0: intrinsics fixed in every mapper (fair with known calibration); 1: refined")
      ->capture_default_str();
  app.add_option("--Compare.num_threads", options.num_threads, "threads of every mapper")
      ->capture_default_str()
      ->check(AtLeast(1, 256));
  app.add_option("--Compare.png_figures", options.png_figures,
                 "1: also the figures as PNG files (report.html shows them interactively)")
      ->capture_default_str();
  if (const std::optional<int> code = ParseOptions(app, argc, argv)) return *code;
  CompareMappers(options);
  return 0;
}

}  // namespace ramap::cli
