#include "feature_options.h"

#include "options.h"
#include "ramap/io/colmap_database_schema.h"

namespace ramap::cli {

void AddExtractionOptions(CLI::App& app, FeatureOptions* o) {
  app.add_option("--ImageReader.camera_model", o->reader.camera_model, "COLMAP camera model")
      ->capture_default_str();
  app.add_option("--ImageReader.camera_params", o->reader.camera_params,
                 "known intrinsics at full resolution, e.g. fx,fy,cx,cy for PINHOLE");
  app.add_option("--ImageReader.single_camera", o->reader.single_camera,
                 "1: one camera for all images")
      ->capture_default_str();
  app.add_option("--ImageReader.default_focal_length_factor", o->reader.default_focal_length_factor,
                 "focal length guess, times the longest side, without camera_params")
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--FeatureExtraction.type", o->type, "orb|sift")->capture_default_str();
  app.add_option("--FeatureExtraction.max_image_size", o->extraction.max_image_size)
      ->capture_default_str()
      ->check(AtLeast(32));
  app.add_option("--FeatureExtraction.max_num_features", o->extraction.max_num_features)
      ->capture_default_str()
      ->check(AtLeast(16));
  app.add_option("--FeatureExtraction.num_threads", o->reader.num_threads)
      ->capture_default_str()
      ->check(AtLeast(1, 256));
  app.add_option("--Database.generation", o->generation_name,
                 "schema of the new database: 3.8 (every COLMAP reads it) | 3.10 | 4 (3.12-4.x)")
      ->capture_default_str();
}

void AddMatchingOptions(CLI::App& app, FeatureOptions* o) {
  app.add_option("--Matching.mode", o->mode,
                 "auto (exhaustive up to --Matching.auto_exhaustive_max_images images, else "
                 "sequential for frame-numbered names, else retrieval)|sequential|exhaustive|"
                 "retrieval")
      ->capture_default_str();
  app.add_option("--Matching.auto_exhaustive_max_images", o->matching.auto_exhaustive_max_images)
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--Matching.overlap", o->matching.overlap,
                 "sequential: each image with its next N")
      ->capture_default_str()
      ->check(AtLeast(1));
  app.add_option("--Matching.loop_num_neighbors", o->matching.loop_num_neighbors,
                 "sequential: each frame also with its N most similar frames (image retrieval) "
                 "at least --Matching.loop_min_frame_gap frames away (0: none)")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--Matching.loop_min_frame_gap", o->matching.loop_min_frame_gap)
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--Matching.retrieval_num_neighbors", o->matching.retrieval_num_neighbors,
                 "retrieval: each image with its N most similar images")
      ->capture_default_str()
      ->check(AtLeast(1));
  app.add_option("--Matching.retrieval_num_words", o->matching.retrieval.num_words,
                 "visual words of the vocabulary trained on the images' own descriptors")
      ->capture_default_str()
      ->check(AtLeast(1));
  app.add_option("--Matching.retrieval_max_features_per_image",
                 o->matching.retrieval.max_features_per_image,
                 "the largest-scale descriptors of an image that describe it for retrieval")
      ->capture_default_str()
      ->check(AtLeast(1));
  app.add_option("--Matching.retrieval_max_training_descriptors",
                 o->matching.retrieval.max_training_descriptors)
      ->capture_default_str()
      ->check(AtLeast(1));
  app.add_option("--Matching.retrieval_num_kmeans_iterations",
                 o->matching.retrieval.num_kmeans_iterations)
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--Matching.max_ratio", o->matching.max_ratio)
      ->capture_default_str()
      ->check(NumberCheck(0, true, 1, false));
  app.add_option("--Matching.cross_check", o->matching.cross_check)->capture_default_str();
  app.add_option("--Matching.max_error_px", o->matching.max_error_px)
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--Matching.min_num_inliers", o->matching.min_num_inliers)
      ->capture_default_str()
      ->check(AtLeast(5));
  app.add_option("--Matching.preemptive_num_features", o->matching.preemptive_num_features,
                 "exhaustive: match the N largest-scale features first, full matching only for "
                 "pairs with enough matches among them (0: off)")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--Matching.preemptive_min_matches", o->matching.preemptive_min_matches)
      ->capture_default_str()
      ->check(AtLeast(1));
  app.add_option("--Matching.num_threads", o->matching.num_threads)
      ->capture_default_str()
      ->check(AtLeast(1, 256));
}

void FinishFeatureOptions(FeatureOptions* o) {
  o->extraction.type = FeatureTypeFromName(o->type);
  o->matching.mode = MatchingModeFromName(o->mode);
  o->generation = DatabaseGenerationFromName(o->generation_name, "--Database.generation");
  o->reader.Check();
  o->extraction.Check();
  o->matching.Check();
}

}  // namespace ramap::cli
