// Shared option parsing for the subcommands (CLI11, COLMAP-style option names such as
// --database_path and --RelativePose.grid_cols).
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace ramap::cli {

// Parses argv into `app`. Returns an exit code when the process should stop now (help was asked
// for, or the options are wrong: CLI11 has printed why), std::nullopt to go on.
inline std::optional<int> ParseOptions(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& help) {
    return app.exit(help);
  } catch (const CLI::ParseError& error) {
    app.exit(error);
    return 2;
  }
  return std::nullopt;
}

}  // namespace ramap::cli
