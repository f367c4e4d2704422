// Shared option parsing for the subcommands (CLI11, COLMAP-style option names such as
// --database_path and --RelativePose.grid_cols).
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
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
    // One line, as every other error: "ramap <command>: error: --Section.option: problem".
    std::cerr << app.get_name() << ": error: " << error.what() << "\n";
    return 2;
  }
  return std::nullopt;
}

// Range checks for numeric options, attached where the option is declared so that every value is
// checked before any work starts. CLI11 reports a failure as "--Section.option: <message>"; the
// message says the allowed range and the value given. NaN and infinities never pass.
inline CLI::Validator NumberCheck(double low, bool low_open, double high, bool high_open) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double value = 0;
        try {
          size_t used = 0;
          value = std::stod(text, &used);
          if (used != text.size()) return "'" + text + "' is not a number";
        } catch (const std::exception&) {
          return "'" + text + "' is not a number";
        }
        const bool ok = std::isfinite(value) && (low_open ? value > low : value >= low) &&
                        (high_open ? value < high : value <= high);
        if (ok) return "";
        std::ostringstream range;
        range << "must be a finite number " << (low_open ? "> " : ">= ") << low;
        if (std::isfinite(high)) range << " and " << (high_open ? "< " : "<= ") << high;
        return range.str() + ", got " + text;
      },
      "", "");
}
// value >= low (and <= high).
inline CLI::Validator AtLeast(double low, double high = std::numeric_limits<double>::infinity()) {
  return NumberCheck(low, false, high, false);
}
// value > low (and < high when high is given).
inline CLI::Validator Above(double low, double high = std::numeric_limits<double>::infinity()) {
  return NumberCheck(low, true, high, true);
}

}  // namespace ramap::cli
