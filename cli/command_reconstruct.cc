// `ramap reconstruct --image_path DIR --output_path DIR`: features, matching and the mapper in one
// command, like `colmap automatic_reconstructor`. Writes DIR/database.db (which COLMAP reads too)
// and DIR/sparse/0, 1, ... with summary.json. After sequential matching, the loop candidates of a
// first solve are matched and verified and the mapper solves again with the loops
// (pipeline/loop_closure.h).
#include <filesystem>
#include <iostream>

#include "feature_options.h"
#include "mapper_options.h"
#include "mapper_report.h"
#include "options.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/point_colors.h"
#include "ramap/pipeline/loop_closure.h"
#include "ramap/pipeline/mapper.h"
#include "ramap/pipeline/mapper_option_table.h"
#include "ramap/pipeline/mapper_output.h"
#include "ramap/pipeline/pose_prior_loading.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"
#include "ramap/util/staged_output.h"

namespace ramap::cli {

int RunReconstruct(int argc, char** argv) {
  CLI::App app("Camera poses and points from a folder of images: features, matching, mapper.",
               "ramap reconstruct");
  std::string image_path, image_list, output_path;
  app.add_option("--image_path", image_path, "folder of the images")->required();
  app.add_option("--image_list", image_list, "only these images (names relative to image_path)");
  app.add_option("--output_path", output_path, "folder for database.db and sparse/")->required();
  FeatureOptions features;
  AddExtractionOptions(app, &features);
  AddMatchingOptions(app, &features);
  MapperOptions mapper;
  AddMapperOptions(app, &mapper);
  bool close_loops = true;
  LoopClosureOptions closure_options;
  AddLoopClosureOptions(app, &close_loops, &closure_options);
  if (const std::optional<int> code = ParseOptions(app, argc, argv)) return *code;
  FinishFeatureOptions(&features);
  ResolveMapperOptions(&mapper);
  CheckFolderOutput("--output_path", output_path, {image_path, image_list});
  const std::string database_path = output_path + "/database.db";
  CheckNewDatabasePath("--output_path", database_path, {image_path, image_list});
  // A run that fails or is interrupted removes what it created (the folder, when it made it).
  CreatedOutput created_folder(output_path);
  CreatedOutput created_database(database_path);

  FeatureDatabase database = ExtractAndReport(image_path, image_list, features);
  const DatabaseMatchingSummary matching = MatchAndReport(&database, &features);
  std::filesystem::create_directories(output_path);
  WriteColmapDatabase(database, database_path, features.generation);
  // EXIF GPS went into the database's prior positions (as COLMAP's ImageReader does).
  const LocalizedPriors priors =
      LoadPosePriors(mapper.prior_source, database, "ramap reconstruct", &std::cerr);
  const bool sequential = features.matching.mode == MatchingMode::kSequential;
  LoopClosedMapperResult closed =
      RunMapperWithLoopClosure(&database, mapper, close_loops && sequential, closure_options,
                               features.matching, database_path, &std::cout, priors.priors);
  // COLMAP gets the loop pairs too.
  if (closed.database_changed) WriteColmapDatabaseMatches(database, database_path);
  MapperResult& result = closed.result;
  ColorModelsFromImages(image_path, &result.reconstructions);
  const nlohmann::json run = {
      {"command", "reconstruct"},
      {"image_path", image_path},
      {"database_path", database_path},
      {"feature_type", features.type},
      {"matching_mode", features.mode},
      {"matching", MatchingSummaryToJson(matching)},
      {"options", OptionValuesToJson(MapperOptionTable(), mapper)},
      {"loop_closure", LoopClosureToJson(close_loops, closure_options, closed.closure)}};
  WriteMapperOutput(result, output_path + "/sparse", ModelFormat::kBinary, run);
  created_database.Keep();
  created_folder.Keep();
  std::cout << "ramap reconstruct: " << result.summary.num_registered_images << " of "
            << database.images.size() << " images registered in " << result.reconstructions.size()
            << " model(s) -> " << output_path << "/sparse\n";
  PrintGeoregistration(result.summary, std::cout);
  return 0;
}

}  // namespace ramap::cli
