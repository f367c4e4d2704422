// `ramap rotation_averager --database_path DB | --relative_poses edges.txt --output_path
// rotations.txt`: stages 1-3 of the mapper (or 2-3 from a relative pose file): robust rotation
// averaging with pruning and the strong-duality certificate on the largest connected view graph,
// one line per image (io/relative_pose_file.h).
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <map>
#include <utility>

#include "options.h"
#include "ramap/estimators/relative_poses.h"
#include "ramap/estimators/rotations.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/relative_pose_file.h"
#include "ramap/mapper/mapper_options.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"

namespace ramap::cli {
namespace {

// Relative poses by image name, from a database (stage 1) or a file, and whether the cameras'
// focal lengths are known (a file's relative poses say nothing of the cameras: not known).
struct LoadedRelativePoses {
  std::vector<RelativePoseRecord> records;
  bool focal_lengths_known = false;
};

LoadedRelativePoses LoadRelativePoses(const std::string& database_path,
                                      const std::string& relative_poses_path,
                                      const MapperOptions& options) {
  if (!relative_poses_path.empty()) return {ReadRelativePoses(relative_poses_path), false};
  const FeatureDatabase database = ReadColmapDatabase(database_path, MapperDatabaseReadOptions());
  const ImageBearings bearings = ComputeBearings(database, database_path);
  std::vector<RelativePoseRecord> records = AcceptedRelativePoses(
      database, EstimateRelativePoses(database, bearings, options.relative_pose,
                                      options.num_threads, &std::cout));
  if (records.empty()) throw InputError(database_path, "no image pair gave a relative pose");
  return {std::move(records), AllFocalLengthsKnown(database)};
}

// Edges outside the largest component were consistent, only not connected to it: they are not
// called pruned.
size_t NumDisconnectedEdges(const RotationAveragingResult& result) {
  return std::count_if(
      result.pruned_edges.begin(), result.pruned_edges.end(),
      [](const PrunedEdge& e) { return e.reason == EdgeStatus::kPrunedDisconnected; });
}

// One line for the run, the phase times and the certificate.
void PrintRotationSummary(const RecordRotations& averaged, const std::string& output_path) {
  const RotationAveragingResult& result = averaged.stage.rotations;
  const RotationCertificate& certificate = result.certificate;
  const RotationAveragingTimings& t = result.timings;
  const size_t num_disconnected = NumDisconnectedEdges(result);
  std::cout << std::fixed << std::setprecision(3)
            << "ramap rotation_averager: " << averaged.rotations.size() << " of "
            << averaged.names.size() << " images, " << averaged.num_edges << " edges ("
            << result.pruned_edges.size() - num_disconnected << " pruned";
  if (num_disconnected > 0) {
    std::cout << ", " << num_disconnected
              << " outside the largest connected component, whose images are not written";
  }
  std::cout << "), "
            << (averaged.sequential
                    ? std::to_string(averaged.stage.num_keyframes) + " keyframes, " +
                          std::to_string(averaged.stage.num_loop_edges) + " loop edges, "
                    : std::string("unordered, "))
            << averaged.seconds << " s -> " << output_path << "\n"
            << "  phases (s): windows " << t.windows << ", init " << t.init << ", L1 " << t.l1
            << ", IRLS " << t.irls << ", pruning " << t.pruning << ", certificate " << t.certificate
            << "\n";
  if (certificate.computed) {
    std::cout << "  certificate: "
              << (certificate.certified ? "certified globally optimal" : "not certified") << " (";
    if (certificate.refinement_skipped) {
      std::cout << "chordal refinement skipped: a triangle of kept edges forces a residual of "
                << certificate.cycle_residual_lower_bound_deg << " deg or more";
    } else {
      std::cout << "max kept residual " << certificate.max_residual_deg << " deg";
    }
    std::cout << ", bound " << certificate.bound_deg << " deg, lambda2 "
              << certificate.fiedler_value << ", d_max " << certificate.max_degree << ")\n";
  }
}

struct RotationAveragerCommand {
  std::string database_path, relative_poses_path, output_path;
  MapperOptions options;
};

const OptionTable<RotationAveragerCommand>& RotationAveragerCommandTable() {
  static const OptionTable<RotationAveragerCommand> table = [] {
    OptionTable<RotationAveragerCommand> t;
    t.push_back(PathOption<RotationAveragerCommand>(
        "database_path", [](auto& o) -> auto& { return o.database_path; },
        "COLMAP database (relative poses first); or --relative_poses"));
    t.push_back(PathOption<RotationAveragerCommand>(
        "relative_poses", [](auto& o) -> auto& { return o.relative_poses_path; },
        "relative pose file written by ramap relative_poses; or --database_path"));
    t.push_back(Required(PathOption<RotationAveragerCommand>(
        "output_path", [](auto& o) -> auto& { return o.output_path; },
        "text file: NAME qw qx qy qz (cam_from_world)")));
    AppendOptions(
        MapperOptionSections({"RelativePose", "ViewGraph", "RotationAveraging"},
                             {"Mapper.num_threads"}),
        [](auto& o) -> auto& { return o.options; }, &t);
    return t;
  }();
  return table;
}

}  // namespace

std::string RotationAveragerOptionsMarkdown() {
  return OptionTableMarkdown(RotationAveragerCommandTable(), RotationAveragerCommand());
}

int RunRotationAverager(int argc, char** argv) {
  CLI::App app("Absolute rotations by robust rotation averaging (L1 + IRLS, pruning, certificate).",
               "ramap rotation_averager");
  RotationAveragerCommand command;
  if (const auto code = ParseCommandLine(app, RotationAveragerCommandTable(), &command, argc, argv))
    return *code;
  const std::string& database_path = command.database_path;
  const std::string& relative_poses_path = command.relative_poses_path;
  const std::string& output_path = command.output_path;
  MapperOptions& options = command.options;
  if (!database_path.empty() && !relative_poses_path.empty()) {
    throw InputError("--relative_poses", "give --database_path or --relative_poses, not both");
  }
  options.Check();
  if (database_path.empty() && relative_poses_path.empty()) {
    throw InputError("rotation_averager", "give --database_path or --relative_poses");
  }
  CheckFileOutput("--output_path", output_path, {database_path, relative_poses_path});

  const LoadedRelativePoses loaded = LoadRelativePoses(database_path, relative_poses_path, options);
  // The edge weighting resolved as the mapper resolves it.
  options.rotation_averaging.use_edge_weights =
      UseRotationEdgeWeights(options.rotation_edge_weights, loaded.focal_lengths_known);
  const RecordRotations averaged = AverageRecordRotations(
      loaded.records, options.order, options.view_graph, options.rotation_averaging);
  WriteRotations(averaged.rotations, output_path);
  PrintRotationSummary(averaged, output_path);
  return 0;
}

}  // namespace ramap::cli
