#include "commands.h"

namespace ramap::cli {

// One function per subcommand, each in its own command_<name>.cc.
int RunDatabaseInfo(int argc, char** argv);

const std::vector<Command>& AllCommands() {
  static const std::vector<Command> commands = {
      {"database_info", "counts and checks what a COLMAP database holds", RunDatabaseInfo},
  };
  return commands;
}

}  // namespace ramap::cli
