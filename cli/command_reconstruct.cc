// `ramap reconstruct --image_path DIR --output_path DIR`: features, matching and the mapper in one
// command, like `colmap automatic_reconstructor`. Writes DIR/database.db (which COLMAP reads too)
// and DIR/sparse/0, 1, ... with summary.json. After sequential matching, the loop candidates of a
// first solve are matched and verified and the mapper solves again with the loops
// (jobs/loop_closure.h).
#include <filesystem>
#include <iostream>

#include "mapper_report.h"
#include "options.h"
#include "ramap/jobs/reconstruct_job.h"

namespace ramap::cli {
namespace {

struct ReconstructCommand {
  ReconstructJob job;
  int log_level = 1;
};

const OptionTable<ReconstructCommand>& ReconstructCommandTable() {
  static const OptionTable<ReconstructCommand> table = [] {
    OptionTable<ReconstructCommand> t;
    t.push_back(Required(PathOption<ReconstructCommand>(
        "image_path", [](auto& o) -> auto& { return o.job.image_path; }, "folder of the images")));
    t.push_back(PathOption<ReconstructCommand>(
        "image_list", [](auto& o) -> auto& { return o.job.image_list; },
        "only these images (names relative to image_path)"));
    t.push_back(Required(PathOption<ReconstructCommand>(
        "output_path", [](auto& o) -> auto& { return o.job.output_path; },
        "folder for database.db and sparse/")));
    t.push_back(LogLevelOption<ReconstructCommand>([](auto& o) -> auto& { return o.log_level; }));
    AppendOptions(
        ReconstructOptionTable(), [](auto& o) -> auto& { return o.job.options; }, &t);
    return t;
  }();
  return table;
}

}  // namespace

std::string ReconstructOptionsMarkdown() {
  return OptionTableMarkdown(ReconstructCommandTable(), ReconstructCommand());
}

int RunReconstruct(int argc, char** argv) {
  CLI::App app("Camera poses and points from a folder of images: features, matching, mapper.",
               "ramap reconstruct");
  ReconstructCommand command;
  if (const auto code = ParseCommandLine(app, ReconstructCommandTable(), &command, argc, argv))
    return *code;
  const ReconstructJob& job = command.job;
  const ReconstructResult result =
      RunReconstructJob(job, ProgressStream(command.log_level), &std::cerr);
  std::cout << "ramap reconstruct: " << result.mapping.summary.num_registered_images << " of "
            << result.num_images << " images registered in "
            << result.mapping.reconstructions.size() << " model(s) -> "
            << (std::filesystem::path(job.output_path) / "sparse").string() << "\n";
  PrintPriorAlignment(result.mapping.summary, std::cout);
  return 0;
}

}  // namespace ramap::cli
