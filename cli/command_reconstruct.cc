// `ramap reconstruct --image_path DIR --output_path DIR`: features, matching and the mapper in one
// command, like `colmap automatic_reconstructor`. Writes DIR/database.db (which COLMAP reads too)
// and DIR/sparse/0, 1, ... with summary.json. After sequential matching, the loop candidates of a
// first solve are matched and verified and the mapper solves again with the loops
// (pipeline/loop_closure.h).
#include <filesystem>
#include <iostream>

#include "mapper_report.h"
#include "options.h"
#include "ramap/pipeline/reconstruct_job.h"

namespace ramap::cli {

int RunReconstruct(int argc, char** argv) {
  CLI::App app("Camera poses and points from a folder of images: features, matching, mapper.",
               "ramap reconstruct");
  ReconstructJob job;
  app.add_option("--image_path", job.image_path, "folder of the images")->required();
  app.add_option("--image_list", job.image_list,
                 "only these images (names relative to image_path)");
  app.add_option("--output_path", job.output_path, "folder for database.db and sparse/")
      ->required();
  AddOptionTable(app, ReconstructOptionTable(), &job.options);
  const LogLevelOption log_level(app);
  if (const std::optional<int> code = ParseOptions(app, argc, argv)) return *code;
  const ReconstructResult result = RunReconstructJob(job, log_level.progress(), &std::cerr);
  std::cout << "ramap reconstruct: " << result.mapping.summary.num_registered_images << " of "
            << result.num_images << " images registered in "
            << result.mapping.reconstructions.size() << " model(s) -> "
            << (std::filesystem::path(job.output_path) / "sparse").string() << "\n";
  PrintPriorAlignment(result.mapping.summary, std::cout);
  return 0;
}

}  // namespace ramap::cli
