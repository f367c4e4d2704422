#include "commands.h"

namespace ramap::cli {

// One function per subcommand, each in its own command_<name>.cc.
int RunDatabaseInfo(int argc, char** argv);
int RunSynthesize(int argc, char** argv);
int RunModelConverter(int argc, char** argv);

const std::vector<Command>& AllCommands() {
  static const std::vector<Command> commands = {
      {"database_info", "counts and checks what a COLMAP database holds", RunDatabaseInfo},
      {"synthesize", "a synthetic scene with exact ground truth (database, model, TUM)",
       RunSynthesize},
      {"model_converter", "convert a COLMAP sparse model between BIN and TXT", RunModelConverter},
  };
  return commands;
}

}  // namespace ramap::cli
