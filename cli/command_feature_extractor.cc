// `ramap feature_extractor --image_path DIR [--image_list FILE] --database_path DB`: OpenCV ORB
// (default) or SIFT features of every image into a new COLMAP database.
#include <iostream>

#include "options.h"
#include "ramap/jobs/reconstruct_job.h"

namespace ramap::cli {
namespace {

struct ExtractorCommand {
  std::string image_path, image_list, database_path;
  FeatureOptions options;
  int log_level = 1;
};

const OptionTable<ExtractorCommand>& ExtractorCommandTable() {
  static const OptionTable<ExtractorCommand> table = [] {
    OptionTable<ExtractorCommand> t;
    t.push_back(Required(PathOption<ExtractorCommand>(
        "image_path", [](auto& o) -> auto& { return o.image_path; }, "folder of the images")));
    t.push_back(PathOption<ExtractorCommand>(
        "image_list", [](auto& o) -> auto& { return o.image_list; },
        "only these images (names relative to image_path)"));
    t.push_back(Required(PathOption<ExtractorCommand>(
        "database_path", [](auto& o) -> auto& { return o.database_path; },
        "the COLMAP database to write")));
    t.push_back(LogLevelOption<ExtractorCommand>([](auto& o) -> auto& { return o.log_level; }));
    AppendOptions(
        ExtractionOptionTable(), [](auto& o) -> auto& { return o.options; }, &t);
    return t;
  }();
  return table;
}

}  // namespace

std::string FeatureExtractorOptionsMarkdown() {
  return OptionTableMarkdown(ExtractorCommandTable(), ExtractorCommand());
}

int RunFeatureExtractor(int argc, char** argv) {
  CLI::App app(
      "Features of a folder or list of images (OpenCV ORB or SIFT) into a COLMAP database.",
      "ramap feature_extractor");
  ExtractorCommand c;
  if (const auto code = ParseCommandLine(app, ExtractorCommandTable(), &c, argc, argv))
    return *code;
  ExtractFeaturesToDatabase(c.image_path, c.image_list, c.database_path, c.options,
                            ProgressStream(c.log_level), &std::cerr);
  std::cout << "Wrote " << c.database_path << "\n";
  return 0;
}

}  // namespace ramap::cli
