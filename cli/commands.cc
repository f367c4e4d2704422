#include "commands.h"

namespace ramap::cli {

// One function per subcommand, each in its own command_<name>.cc.

const std::vector<Command>& AllCommands() {
  static const std::vector<Command> commands = {
  };
  return commands;
}

}  // namespace ramap::cli
