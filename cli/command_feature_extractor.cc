// `ramap feature_extractor --image_path DIR [--image_list FILE] --database_path DB`: OpenCV ORB
// (default) or SIFT features of every image into a new COLMAP database.
#include <iomanip>
#include <iostream>

#include "feature_options.h"
#include "options.h"
#include "ramap/io/colmap_database.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"

namespace ramap::cli {

FeatureDatabase ExtractAndReport(const std::string& image_path, const std::string& image_list,
                                 const FeatureOptions& options) {
  const std::vector<std::string> names = ListImages(image_path, image_list);
  ExtractionSummary summary;
  FeatureDatabase database = ExtractImageFeatures(image_path, names, options.reader,
                                                  options.extraction, &summary, &std::cout);
  for (const std::string& skipped : summary.skipped_images) {
    std::cerr << "ramap: warning: skipped " << image_path << "/" << skipped << "\n";
  }
  if (summary.num_images == 0) throw InputError(image_path, "no image could be read");
  std::cout << "[ramap] features: " << summary.num_images << " of " << names.size() << " images ("
            << FeatureTypeName(options.extraction.type) << "), "
            << summary.num_keypoints / std::max(1, summary.num_images) << " keypoints each on "
            << "average, " << database.cameras.size() << " camera(s), " << std::fixed
            << std::setprecision(2) << summary.seconds << " s";
  if (summary.num_images_with_gps > 0) {
    std::cout << ", EXIF GPS of " << summary.num_images_with_gps << " stored as prior positions";
  }
  std::cout << "\n";
  return database;
}

int RunFeatureExtractor(int argc, char** argv) {
  CLI::App app(
      "Features of a folder or list of images (OpenCV ORB or SIFT) into a COLMAP database.",
      "ramap feature_extractor");
  std::string image_path, image_list, database_path;
  app.add_option("--image_path", image_path, "folder of the images")->required();
  app.add_option("--image_list", image_list, "only these images (names relative to image_path)");
  app.add_option("--database_path", database_path, "the COLMAP database to write")->required();
  FeatureOptions options;
  AddExtractionOptions(app, &options);
  if (const std::optional<int> code = ParseOptions(app, argc, argv)) return *code;
  FinishFeatureOptions(&options);
  CheckNewDatabasePath("--database_path", database_path, {image_path, image_list});
  const FeatureDatabase database = ExtractAndReport(image_path, image_list, options);
  WriteColmapDatabase(database, database_path, options.generation);
  std::cout << "Wrote " << database_path << "\n";
  return 0;
}

}  // namespace ramap::cli
