#include "commands.h"

namespace ramap::cli {

// One function per subcommand, each in its own command_<name>.cc.
int RunDatabaseInfo(int argc, char** argv);
int RunMapper(int argc, char** argv);
int RunModelConverter(int argc, char** argv);
int RunEvaluate(int argc, char** argv);

const std::vector<Command>& AllCommands() {
  static const std::vector<Command> commands = {
      {"database_info", "counts and checks what a COLMAP database holds", RunDatabaseInfo},
      {"mapper", "camera poses and points from a COLMAP database by motion averaging", RunMapper},
      {"model_converter", "convert a COLMAP sparse model between BIN and TXT", RunModelConverter},
      {"evaluate", "score a model's camera poses against ground truth (ATE, AUC)", RunEvaluate},
  };
  return commands;
}

}  // namespace ramap::cli
