// `ramap compare --database_path DB --output_path DIR [--image_path DIR] [--ground_truth PATH
// --ground_truth_format FORMAT] [--peer_colmap PATH]`: COLMAP's BA mapper, the peers (COLMAP 4's
// incremental mapper and GLOMAP) when given, and ramap's averaging mapper with and without BA, on
// the same database (compare/compare_mappers.h). Writes DIR/report.html, DIR/report.md and
// DIR/report.json.
#include "options.h"
#include "ramap/compare/compare_mappers.h"

namespace ramap::cli {

std::string CompareOptionsMarkdown() {
  return OptionTableMarkdown(CompareOptionTable(), CompareOptions());
}

int RunCompare(int argc, char** argv) {
  CLI::App app(
      "COLMAP's BA mapper vs ramap's averaging mapper (with and without BA) on one database, with "
      "COLMAP 4 and GLOMAP as peers when given: accuracy, time and figures.",
      "ramap compare");
  CompareOptions options;
  if (const auto code = ParseCommandLine(app, CompareOptionTable(), &options, argc, argv))
    return *code;
  CompareMappers(options);
  return 0;
}

}  // namespace ramap::cli
