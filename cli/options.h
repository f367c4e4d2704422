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
#include <vector>

#include "ramap/util/option_table.h"

namespace ramap::cli {

// Registers every declaration of `table` as --Section.option, bound to `settings`: its help, its
// default (the value `settings` holds now) and its value hint come from the declaration, and a
// value it refuses stops parsing with the declaration's message ("--Section.option: problem"),
// the one a library or Python caller gets too.
template <typename Settings>
void AddOptionTable(CLI::App& app, const OptionTable<Settings>& table, Settings* settings) {
  for (const OptionDeclaration<Settings>& declaration : table) {
    std::string help = declaration.help;
    const bool bounded =
        std::isfinite(declaration.range.low) || std::isfinite(declaration.range.high);
    if ((declaration.type == OptionType::kInteger || declaration.type == OptionType::kNumber) &&
        bounded) {
      help +=
          " (" + OptionValueHint(declaration.type, declaration.range, declaration.choices) + ")";
    }
    std::string names = "--" + declaration.name;
    for (const std::string& former : declaration.former_names) names += ",--" + former;
    CLI::Option* option = app.add_option(
        names,
        [declaration, settings](const CLI::results_t& values) {
          try {
            SetOption(declaration, values.front(), settings);
          } catch (const InputError& error) {
            throw CLI::ValidationError(error.what());
          }
          return true;
        },
        help);
    option->default_str(declaration.text(*settings));
    option->type_name(OptionTypeName(declaration.type, declaration.choices));
    option->expected(1);
  }
}

// Parses argv into `app`. Returns an exit code when the process should stop now (help was asked
// for, or the options are wrong: CLI11 has printed why), std::nullopt to go on.
inline std::optional<int> ParseOptions(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& help) {
    return app.exit(help);
  } catch (const CLI::ExtrasError&) {
    // An unknown option, said as the library says it to a Python caller, with the nearest name.
    std::vector<std::string> known;
    for (const CLI::Option* option : app.get_options()) {
      for (const std::string& name : option->get_lnames()) known.push_back(name);
    }
    for (const std::string& extra : app.remaining()) {
      if (extra.rfind("--", 0) != 0) continue;
      const std::string name = extra.substr(2, extra.find('=') - 2);
      std::cerr << app.get_name() << ": error: --" << name << ": "
                << UnknownOptionMessage(name, known) << "\n";
      return 2;
    }
    std::cerr << app.get_name() << ": error: unexpected arguments";
    for (const std::string& extra : app.remaining()) std::cerr << " " << extra;
    std::cerr << "\n";
    return 2;
  } catch (const CLI::ParseError& error) {
    // One line, as every other error: "ramap <command>: error: --Section.option: problem".
    std::cerr << app.get_name() << ": error: " << error.what() << "\n";
    return 2;
  }
  return std::nullopt;
}

// --log_level of the commands that do long work: 0 prints the result alone; 1 (the default, and any
// higher level) also one line per stage and, on a terminal, a progress line redrawn in place while
// a stage works (util/progress_line.h). progress() says where it goes: std::cout, or nullptr at 0.
class LogLevelOption {
 public:
  explicit LogLevelOption(CLI::App& app) {
    app.add_option("--log_level", level_,
                   "0: the result alone; 1: one line per stage, and a progress line on a terminal")
        ->capture_default_str()
        ->check(CLI::NonNegativeNumber);
  }
  std::ostream* progress() const { return level_ > 0 ? &std::cout : nullptr; }

 private:
  int level_ = 1;
};

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
