// `ramap feature_extractor --image_path DIR [--image_list FILE] --database_path DB`: OpenCV ORB
// (default) or SIFT features of every image into a new COLMAP database.
#include <iostream>

#include "options.h"
#include "ramap/pipeline/reconstruct_job.h"

namespace ramap::cli {

int RunFeatureExtractor(int argc, char** argv) {
  CLI::App app(
      "Features of a folder or list of images (OpenCV ORB or SIFT) into a COLMAP database.",
      "ramap feature_extractor");
  std::string image_path, image_list, database_path;
  app.add_option("--image_path", image_path, "folder of the images")->required();
  app.add_option("--image_list", image_list, "only these images (names relative to image_path)");
  app.add_option("--database_path", database_path, "the COLMAP database to write")->required();
  FeatureOptions options;
  AddOptionTable(app, ExtractionOptionTable(), &options);
  const LogLevelOption log_level(app);
  if (const std::optional<int> code = ParseOptions(app, argc, argv)) return *code;
  ExtractFeaturesToDatabase(image_path, image_list, database_path, options, log_level.progress(),
                            &std::cerr);
  std::cout << "Wrote " << database_path << "\n";
  return 0;
}

}  // namespace ramap::cli
