#include "commands.h"

namespace ramap::cli {

// One function per subcommand, each in its own command_<name>.cc.
int RunCompare(int argc, char** argv);
int RunDatabaseInfo(int argc, char** argv);
int RunEvaluate(int argc, char** argv);
int RunFeatureExtractor(int argc, char** argv);
int RunMatcher(int argc, char** argv);
int RunReconstruct(int argc, char** argv);
int RunMapper(int argc, char** argv);
int RunModelAligner(int argc, char** argv);
int RunModelConverter(int argc, char** argv);
int RunRelativePoses(int argc, char** argv);
int RunRotationAverager(int argc, char** argv);
int RunSynthesize(int argc, char** argv);

const std::vector<Command>& AllCommands() {
  static const std::vector<Command> commands = {
      {"reconstruct", "images to a COLMAP model: features, matching, mapper", RunReconstruct},
      {"feature_extractor", "ORB or SIFT features of images into a COLMAP database",
       RunFeatureExtractor},
      {"matcher", "matches and verified geometries (sequential or exhaustive)", RunMatcher},
      {"mapper", "camera poses and points from a COLMAP database by motion averaging", RunMapper},
      {"relative_poses", "relative pose of every verified pair (grid 6-point, Kneip)",
       RunRelativePoses},
      {"rotation_averager", "absolute rotations by robust rotation averaging, certified",
       RunRotationAverager},
      {"evaluate", "score a model's camera poses against ground truth (ATE, AUC)", RunEvaluate},
      {"compare", "COLMAP's BA mapper vs ramap on one database: accuracy, time, figures",
       RunCompare},
      {"database_info", "counts and checks what a COLMAP database holds", RunDatabaseInfo},
      {"model_aligner", "georegister a COLMAP model to GPS / position priors (ENU, GeoJSON)",
       RunModelAligner},
      {"model_converter", "convert a COLMAP sparse model between BIN and TXT", RunModelConverter},
      {"synthesize", "a synthetic scene with exact ground truth (database, model, TUM)",
       RunSynthesize},
  };
  return commands;
}

}  // namespace ramap::cli
