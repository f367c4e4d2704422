// The subcommands of `ramap`. Each parses its own options (COLMAP-style names) and returns the
// process exit code; errors a user can act on are thrown as InputError and reported by main.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace ramap::cli {

struct Command {
  std::string name;
  std::string summary;
  std::function<int(int argc, char** argv)> run;
};

// Every command, in the order `ramap help` lists them.
const std::vector<Command>& AllCommands();

}  // namespace ramap::cli
