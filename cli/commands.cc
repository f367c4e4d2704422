#include "commands.h"

namespace ramap::cli {

// One function per subcommand, each in its own command_<name>.cc.
int RunModelConverter(int argc, char** argv);

const std::vector<Command>& AllCommands() {
  static const std::vector<Command> commands = {
      {"model_converter", "Convert a COLMAP sparse model between BIN and TXT", RunModelConverter},
  };
  return commands;
}

}  // namespace ramap::cli
