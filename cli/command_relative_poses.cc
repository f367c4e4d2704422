// `ramap relative_poses --database_path DB --output_path edges.txt`: stage 1 of the mapper on its
// own: the relative pose of every verified pair of a COLMAP database (grid-selected six points and
// Kneip's rotation-only solvers by default), one line per accepted edge (io/relative_pose_file.h),
// and a count of the rejected pairs by reason.
#include <iomanip>
#include <iostream>
#include <map>

#include "options.h"
#include "ramap/estimators/relative_poses.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/relative_pose_file.h"
#include "ramap/mapper/mapper_options.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"
#include "ramap/util/timer.h"

namespace ramap::cli {
namespace {

struct RelativePosesCommand {
  std::string database_path, output_path;
  MapperOptions options;
};

const OptionTable<RelativePosesCommand>& RelativePosesCommandTable() {
  static const OptionTable<RelativePosesCommand> table = [] {
    OptionTable<RelativePosesCommand> t;
    t.push_back(Required(PathOption<RelativePosesCommand>(
        "database_path", [](auto& o) -> auto& { return o.database_path; },
        "COLMAP database with verified matches")));
    t.push_back(Required(PathOption<RelativePosesCommand>(
        "output_path", [](auto& o) -> auto& { return o.output_path; },
        "text file: NAME1 NAME2 qw qx qy qz tx ty tz num_inliers flags")));
    AppendOptions(
        MapperOptionSections({"RelativePose"}, {"Mapper.num_threads"}),
        [](auto& o) -> auto& { return o.options; }, &t);
    return t;
  }();
  return table;
}

}  // namespace

std::string RelativePosesOptionsMarkdown() {
  return OptionTableMarkdown(RelativePosesCommandTable(), RelativePosesCommand());
}

int RunRelativePoses(int argc, char** argv) {
  CLI::App app("Relative pose of every verified image pair of a COLMAP database.",
               "ramap relative_poses");
  RelativePosesCommand command;
  if (const auto code = ParseCommandLine(app, RelativePosesCommandTable(), &command, argc, argv))
    return *code;
  const std::string& database_path = command.database_path;
  const std::string& output_path = command.output_path;
  MapperOptions& options = command.options;
  options.Check();
  CheckFileOutput("--output_path", output_path, {database_path});

  const FeatureDatabase database = ReadColmapDatabase(database_path, MapperDatabaseReadOptions());
  const ImageBearings bearings = ComputeBearings(database, database_path);
  Timer timer;
  const std::vector<ImagePair> edges = EstimateRelativePoses(
      database, bearings, options.relative_pose, options.num_threads, &std::cout);
  const double seconds = timer.ElapsedSeconds();

  const std::vector<RelativePoseRecord> records = AcceptedRelativePoses(database, edges);
  // Rejections by kind, each with its first pair's reason as the example.
  std::map<RelativePoseRejection, std::pair<int, std::string>> rejected;
  for (const ImagePair& edge : edges) {
    if (edge.estimate.success) continue;
    auto& [count, example] = rejected[edge.estimate.rejection];
    if (count++ == 0) example = edge.estimate.reason;
  }
  if (records.empty()) {
    throw InputError(database_path,
                     edges.empty() ? "no image pair has verified matches with a usable geometry "
                                     "(run a COLMAP matcher first)"
                                   : "every one of the " + std::to_string(edges.size()) +
                                         " verified pairs was rejected");
  }
  WriteRelativePoses(records, output_path);
  std::cout << "ramap relative_poses: " << records.size() << " of " << edges.size()
            << " verified pairs (" << CorrespondenceSamplerName(options.relative_pose.sampler)
            << " sampler) in " << std::fixed << std::setprecision(2) << seconds << " s ("
            << std::setprecision(3) << 1000.0 * seconds / edges.size() << " ms per pair on "
            << options.num_threads << " threads) -> " << output_path << "\n";
  for (const auto& [kind, count_and_example] : rejected) {
    std::cout << "  rejected " << count_and_example.first << ": " << RelativePoseRejectionName(kind)
              << " (e.g. " << count_and_example.second << ")\n";
  }
  return 0;
}

}  // namespace ramap::cli
