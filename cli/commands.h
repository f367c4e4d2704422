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
  // Its options as a Markdown table, from the one table the command parses (empty: none of its
  // own, as COLMAP's matcher names that run `matcher`).
  std::function<std::string()> options_markdown;
};

// Every command, in the order `ramap help` lists them.
const std::vector<Command>& AllCommands();

}  // namespace ramap::cli
