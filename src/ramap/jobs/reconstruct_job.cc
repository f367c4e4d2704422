#include "ramap/jobs/reconstruct_job.h"

#include <algorithm>
#include <filesystem>
#include <iomanip>

#include "ramap/io/colmap_database.h"
#include "ramap/io/point_colors.h"
#include "ramap/jobs/loop_closure.h"
#include "ramap/jobs/mapper_output.h"
#include "ramap/jobs/pose_prior_loading.h"
#include "ramap/mapper/mapper_options.h"
#include "ramap/util/blas_threads.h"
#include "ramap/util/error.h"
#include "ramap/util/option_json.h"
#include "ramap/util/output_policy.h"
#include "ramap/util/staged_output.h"

namespace ramap {

FeatureDatabase ExtractFeatures(const std::string& image_path, const std::string& image_list,
                                const FeatureOptions& options, std::ostream* progress,
                                std::ostream* warnings, ExtractionSummary* extraction) {
  const std::vector<std::string> names = ListImages(image_path, image_list);
  ExtractionSummary local;
  ExtractionSummary& summary = extraction != nullptr ? *extraction : local;
  FeatureDatabase database = ExtractImageFeatures(image_path, names, options.reader,
                                                  options.extraction, &summary, progress);
  for (const std::string& skipped : summary.skipped_images) {
    if (warnings != nullptr)
      *warnings << "ramap: warning: skipped " << image_path << "/" << skipped << "\n";
  }
  if (summary.num_images == 0) throw InputError(image_path, "no image could be read");
  if (progress == nullptr) return database;
  *progress << "[ramap] features: " << summary.num_images << " of " << names.size() << " images ("
            << FeatureTypeName(options.extraction.type) << "), "
            << summary.num_keypoints / std::max(1, summary.num_images) << " keypoints each on "
            << "average, " << database.cameras.size() << " camera(s), " << std::fixed
            << std::setprecision(2) << summary.seconds << " s";
  if (summary.num_images_with_gps > 0) {
    *progress << ", EXIF GPS of " << summary.num_images_with_gps << " stored as prior positions";
  }
  *progress << "\n";
  return database;
}

namespace {

void PrintMatchingPlan(const DatabaseMatchingSummary& summary, std::ostream& out) {
  out << std::fixed << std::setprecision(2)
      << "[ramap] matching plan: " << MatchingModeName(summary.mode) << " (" << summary.reason
      << "): ";
  const bool retrieval = summary.mode == MatchingMode::kRetrieval;
  if (summary.num_unscreened_pairs > 0 || retrieval) {
    out << summary.num_unscreened_pairs << (retrieval ? " retrieved pairs" : " neighbour pairs");
  }
  if (!retrieval) {
    out << (summary.num_unscreened_pairs > 0 ? ", " : "") << summary.num_pairs_to_screen
        << (summary.mode == MatchingMode::kSequential ? " loop candidates" : " pairs");
  }
  if (summary.retrieval_seconds > 0) out << " (retrieval " << summary.retrieval_seconds << " s)";
  if (summary.num_pairs_to_screen > 0) {
    out << ", " << summary.num_pairs_kept_by_screening << " of them kept by preemptive matching ("
        << summary.screening_seconds << " s)";
  }
  out << "\n[ramap] matching: " << summary.num_verified_pairs << " of " << summary.num_pairs
      << " pairs verified, " << summary.seconds << " s\n";
}

}  // namespace

DatabaseMatchingSummary MatchFeatures(FeatureDatabase* database, FeatureOptions* options,
                                      std::ostream* progress) {
  const DatabaseMatchingSummary summary = MatchDatabase(database, options->matching, progress);
  options->matching.mode = summary.mode;
  if (progress != nullptr) PrintMatchingPlan(summary, *progress);
  return summary;
}

nlohmann::json MatchingSummaryToJson(const DatabaseMatchingSummary& summary) {
  return {{"mode", MatchingModeName(summary.mode)},
          {"reason", summary.reason},
          {"pairs_matched_unscreened", summary.num_unscreened_pairs},
          {"pairs_to_screen", summary.num_pairs_to_screen},
          {"pairs_kept_by_preemptive_matching", summary.num_pairs_kept_by_screening},
          {"pairs_matched", summary.num_pairs},
          {"pairs_verified", summary.num_verified_pairs},
          {"retrieval_seconds", summary.retrieval_seconds},
          {"preemptive_matching_seconds", summary.screening_seconds},
          {"seconds", summary.seconds}};
}

size_t ExtractFeaturesToDatabase(const std::string& image_path, const std::string& image_list,
                                 const std::string& database_path, FeatureOptions options,
                                 std::ostream* progress, std::ostream* warnings) {
  ResolveFeatureOptions(&options);
  CheckNewDatabasePath("--database_path", database_path, {image_path, image_list});
  const FeatureDatabase database =
      ExtractFeatures(image_path, image_list, options, progress, warnings);
  WriteColmapDatabase(database, database_path, options.generation);
  return database.images.size();
}

DatabaseMatchingSummary MatchDatabaseFile(const std::string& database_path, FeatureOptions options,
                                          std::ostream* progress) {
  ResolveFeatureOptions(&options);
  DatabaseReadOptions read_options;
  read_options.read_descriptors = true;
  read_options.read_matches = false;
  FeatureDatabase database = ReadColmapDatabase(database_path, read_options);
  const DatabaseMatchingSummary summary = MatchFeatures(&database, &options, progress);
  WriteColmapDatabaseMatches(database, database_path);
  return summary;
}

ReconstructResult RunReconstructJob(const ReconstructJob& job, std::ostream* progress,
                                    std::ostream* warnings) {
  ReconstructOptions options = job.options;
  ResolveReconstructOptions(&options);
  // The mapper's threads for the BLAS throughout, loop closure's matching included.
  const ScopedBlasThreads blas_threads(options.mapper.num_threads);
  CheckFolderOutput("--output_path", job.output_path, {job.image_path, job.image_list});
  const std::string database_path = job.output_path + "/database.db";
  CheckNewDatabasePath("--output_path", database_path, {job.image_path, job.image_list});
  // A run that fails or is interrupted removes what it created (the folder, when it made it).
  CreatedOutput created_folder(job.output_path);
  CreatedOutput created_database(database_path);

  FeatureOptions& features = options.features;
  ExtractionSummary extraction;
  FeatureDatabase database =
      ExtractFeatures(job.image_path, job.image_list, features, progress, warnings, &extraction);
  const DatabaseMatchingSummary matching = MatchFeatures(&database, &features, progress);
  std::filesystem::create_directories(job.output_path);
  WriteColmapDatabase(database, database_path, features.generation);
  // EXIF GPS went into the database's prior positions (as COLMAP's ImageReader does).
  const LocalizedPriors priors =
      LoadPosePriors(options.mapper.prior_source, database, job.command, warnings);
  const bool sequential = features.matching.mode == MatchingMode::kSequential;
  LoopClosedMapperResult closed = RunMapperWithLoopClosure(
      &database, options.mapper, options.close_loops && sequential, options.loop_closure,
      features.matching, database_path, progress, priors.priors);
  // COLMAP gets the loop pairs too.
  if (closed.database_changed) WriteColmapDatabaseMatches(database, database_path);
  ReconstructResult result{std::move(closed.result), database.images.size()};
  for (CameraIntrinsicsSummary& camera : result.mapping.summary.cameras) {
    const auto source = extraction.focal_sources.find(camera.camera_id);
    if (source != extraction.focal_sources.end()) camera.focal_source = source->second;
  }
  ColorModelsFromImages(job.image_path, &result.mapping.reconstructions);
  const nlohmann::json run = {
      {"command", "reconstruct"},
      {"image_path", job.image_path},
      {"database_path", database_path},
      {"feature_type", FeatureTypeName(features.extraction.type)},
      {"matching_mode", MatchingModeName(features.matching.mode)},
      {"matching", MatchingSummaryToJson(matching)},
      {"options", OptionValuesToJson(MapperOptionTable(), options.mapper)},
      {"pose_priors",
       PosePriorOptionsToJson(options.mapper.prior_source, options.mapper.prior_alignment)},
      {"loop_closure",
       LoopClosureToJson(options.close_loops, options.loop_closure, closed.closure)}};
  WriteMapperOutput(result.mapping, job.output_path + "/sparse", ModelFormat::kBinary, run,
                    warnings, options.mapper.num_threads);
  created_database.Keep();
  created_folder.Keep();
  return result;
}

}  // namespace ramap
