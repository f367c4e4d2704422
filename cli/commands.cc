#include "commands.h"

#include <string>

namespace ramap::cli {

// One function per subcommand, each in its own command_<name>.cc.
int RunCompare(int argc, char** argv);
int RunDatabaseInfo(int argc, char** argv);
int RunOptions(int argc, char** argv);
int RunDatabaseConverter(int argc, char** argv);
int RunEvaluate(int argc, char** argv);
int RunFeatureExtractor(int argc, char** argv);
int RunMatcher(int argc, char** argv);
int RunBundleAdjuster(int argc, char** argv);
int RunImageUndistorter(int argc, char** argv);
int RunReconstruct(int argc, char** argv);
int RunMapper(int argc, char** argv);
int RunModelAligner(int argc, char** argv);
int RunModelConverter(int argc, char** argv);
int RunRelativePoses(int argc, char** argv);
int RunRotationAverager(int argc, char** argv);
int RunSynthesize(int argc, char** argv);

// Their options, each from the command's own table.
std::string BundleAdjusterOptionsMarkdown();
std::string CompareOptionsMarkdown();
std::string DatabaseConverterOptionsMarkdown();
std::string DatabaseInfoOptionsMarkdown();
std::string EvaluateOptionsMarkdown();
std::string FeatureExtractorOptionsMarkdown();
std::string ImageUndistorterOptionsMarkdown();
std::string MapperOptionsMarkdown();
std::string MatcherOptionsMarkdown();
std::string ModelAlignerOptionsMarkdown();
std::string ModelConverterOptionsMarkdown();
std::string ReconstructOptionsMarkdown();
std::string RelativePosesOptionsMarkdown();
std::string RotationAveragerOptionsMarkdown();
std::string SynthesizeOptionsMarkdown();

// COLMAP's exhaustive_matcher and sequential_matcher: ramap's matcher in that mode.
int RunMatcherInMode(const char* mode, int argc, char** argv) {
  std::vector<char*> args(argv, argv + argc);
  char option[] = "--Matching.mode";
  std::string value = mode;
  args.insert(args.begin() + 1, {option, value.data()});
  args.push_back(nullptr);
  return RunMatcher(argc + 2, args.data());
}

const std::vector<Command>& AllCommands() {
  static const std::vector<Command> commands = {
      {"reconstruct", "images to a COLMAP model: features, matching, mapper", RunReconstruct,
       ReconstructOptionsMarkdown},
      {"feature_extractor", "ORB or SIFT features of images into a COLMAP database",
       RunFeatureExtractor, FeatureExtractorOptionsMarkdown},
      {"matcher", "matches and verified geometries (sequential, retrieval or exhaustive)",
       RunMatcher, MatcherOptionsMarkdown},
      {"exhaustive_matcher", "as COLMAP's: matcher --Matching.mode exhaustive",
       [](int argc, char** argv) { return RunMatcherInMode("exhaustive", argc, argv); }},
      {"sequential_matcher", "as COLMAP's: matcher --Matching.mode sequential",
       [](int argc, char** argv) { return RunMatcherInMode("sequential", argc, argv); }},
      // nerfstudio's default: image retrieval, with a vocabulary trained on the images themselves
      // instead of a downloaded tree.
      {"vocab_tree_matcher", "as COLMAP's: matcher --Matching.mode retrieval",
       [](int argc, char** argv) { return RunMatcherInMode("retrieval", argc, argv); }},
      {"mapper", "camera poses and points from a COLMAP database by motion averaging", RunMapper,
       MapperOptionsMarkdown},
      {"relative_poses", "relative pose of every verified pair (grid 6-point, Kneip)",
       RunRelativePoses, RelativePosesOptionsMarkdown},
      {"rotation_averager", "absolute rotations by robust rotation averaging, certified",
       RunRotationAverager, RotationAveragerOptionsMarkdown},
      {"evaluate", "score a model's camera poses against ground truth (ATE, AUC)", RunEvaluate,
       EvaluateOptionsMarkdown},
      {"compare", "COLMAP's BA mapper vs ramap on one database: accuracy, time, figures",
       RunCompare, CompareOptionsMarkdown},
      {"database_info", "counts and checks what a COLMAP database holds", RunDatabaseInfo,
       DatabaseInfoOptionsMarkdown},
      {"options", "every option, its default and meaning (Markdown)", RunOptions},
      {"database_converter", "a COLMAP database rewritten as another generation (3.8, 3.10, 4)",
       RunDatabaseConverter, DatabaseConverterOptionsMarkdown},
      {"model_aligner", "align a COLMAP model to GPS / pose priors (ENU, GeoJSON)", RunModelAligner,
       ModelAlignerOptionsMarkdown},
      {"model_converter", "convert a COLMAP sparse model between BIN and TXT", RunModelConverter,
       ModelConverterOptionsMarkdown},
      {"bundle_adjuster", "bundle adjustment of a COLMAP model (poses, points, intrinsics)",
       RunBundleAdjuster, BundleAdjusterOptionsMarkdown},
      {"image_undistorter", "undistorted images and PINHOLE model (COLMAP's layout, for 3DGS)",
       RunImageUndistorter, ImageUndistorterOptionsMarkdown},
      {"synthesize", "a synthetic scene with exact ground truth (database, model, TUM)",
       RunSynthesize, SynthesizeOptionsMarkdown},
  };
  return commands;
}

}  // namespace ramap::cli
