#include "ramap/jobs/mapper_job.h"

#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_database_schema.h"
#include "ramap/io/database_rigs_priors.h"
#include "ramap/io/point_colors.h"
#include "ramap/jobs/mapper_output.h"
#include "ramap/jobs/pose_prior_loading.h"
#include "ramap/mapper/mapper_options.h"
#include "ramap/mapper/stage_log.h"
#include "ramap/util/option_json.h"
#include "ramap/util/output_policy.h"
#include "ramap/util/timer.h"

namespace ramap {

namespace {

void ColorPoints(const MapperJob& job, std::ostream* progress, std::ostream* warnings,
                 MapperResult* result) {
  Timer timer;
  const PointColorSummary colors = ColorModelsFromImages(job.image_path, &result->reconstructions);
  if (progress != nullptr) {
    PrintStageLine(
        *progress, "point colours", timer.ElapsedSeconds(),
        "from " + std::to_string(colors.num_images_read) + " images in " + job.image_path);
  }
  if (warnings == nullptr) return;
  for (const std::string& name : colors.unreadable_images) {
    *warnings << job.command << ": warning: cannot read " << job.image_path << "/" << name
              << ": its points keep no colour from it\n";
  }
}

}  // namespace

MapperResult RunMapperJob(const MapperJob& job, std::ostream* progress, std::ostream* warnings) {
  MapperOptions options = job.options;
  options.Check();
  if (!job.output_path.empty()) {
    CheckFolderOutput("--output_path", job.output_path,
                      {job.database_path, job.image_path, options.prior_source.path});
  }
  Timer read_timer;
  const FeatureDatabase database =
      ReadColmapDatabase(job.database_path, MapperDatabaseReadOptions());
  const RigSummary rigs = SummarizeRigs(database);
  if (progress != nullptr) {
    PrintStageLine(*progress, "reading the database", read_timer.ElapsedSeconds(),
                   std::to_string(database.images.size()) + " images, " +
                       std::to_string(database.two_view_geometries.size()) + " verified pairs, " +
                       DatabaseGenerationLabel(database.generation));
  }
  if (rigs.num_multi_camera_frames > 0 && warnings != nullptr) {
    *warnings << job.command << ": note: " << rigs.num_multi_camera_frames << " of "
              << rigs.num_frames << " frames hold images of up to " << rigs.max_cameras_per_frame
              << " cameras of one rig; the rig constraints are not used yet: each image is "
                 "averaged on its own\n";
  }
  if (!job.output_path.empty()) {
    CheckImageNamesFit(
        database, job.output_format, job.database_path,
        job.output_format == ModelFormat::kText
            ? "the text format was asked for by --output_type TXT; --output_type BIN holds it"
            : "--output_type BIN");
  }
  const LocalizedPriors priors =
      LoadPosePriors(options.prior_source, database, job.command, warnings);
  MapperResult result = RunMapper(database, options, job.database_path, progress, priors.priors);
  if (!job.image_path.empty()) ColorPoints(job, progress, warnings, &result);
  if (job.output_path.empty()) return result;
  const nlohmann::json run = {
      {"command", "mapper"},
      {"database_path", job.database_path},
      {"image_path", job.image_path},
      {"database",
       {{"generation", DatabaseGenerationLabel(database.generation)},
        {"num_rigs", rigs.num_rigs},
        {"num_frames", rigs.num_frames},
        {"num_multi_camera_frames", rigs.num_multi_camera_frames},
        {"rig_constraints_used", false}}},
      {"options", OptionValuesToJson(MapperOptionTable(), options)},
      {"pose_priors", PosePriorOptionsToJson(options.prior_source, options.prior_alignment)}};
  Timer write_timer;
  WriteMapperOutput(result, job.output_path, job.output_format, run, warnings, options.num_threads);
  if (progress != nullptr) {
    PrintStageLine(*progress, "writing the models", write_timer.ElapsedSeconds(), job.output_path);
  }
  return result;
}

}  // namespace ramap
