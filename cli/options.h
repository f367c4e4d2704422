// The command line of every subcommand: one table of declarations (util/option_table.h) per
// command, registered with CLI11 under COLMAP-style names (--database_path,
// --RelativePose.grid_cols) and the aliases the declarations carry.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "ramap/io/colmap_model.h"
#include "ramap/util/error.h"
#include "ramap/util/option_table.h"

namespace ramap::cli {

// Registers every declaration of `table` as --name, bound to `settings`: its help, its default
// (the value `settings` holds now) and its value hint come from the declaration, and a value it
// refuses stops parsing with the declaration's message ("--Section.option: problem"), the one a
// library or Python caller gets too. Former names are shown beside the name; COLMAP's names are
// accepted with a note on the standard error saying how they were read, and COLMAP's options that
// mean nothing here with a note saying why they are ignored.
template <typename Settings>
void AddOptionTable(CLI::App& app, const OptionTable<Settings>& table, Settings* settings) {
  for (const OptionDeclaration<Settings>& declaration : table) {
    if (!declaration.ignored_because.empty()) {
      app.add_option(
             "--" + declaration.name,
             [declaration](const CLI::results_t& values) {
               std::cerr << "ramap: note: --" << declaration.name << " " << values.front()
                         << " ignored: " << declaration.ignored_because << "\n";
               return true;
             },
             declaration.help)
          ->expected(1)
          ->group("");
      continue;
    }
    const auto store = [declaration, settings](const std::string& value) {
      try {
        SetOption(declaration, value, settings);
      } catch (const InputError& error) {
        throw CLI::ValidationError(error.what());
      }
    };
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
        [store](const CLI::results_t& values) {
          store(values.front());
          return true;
        },
        help);
    option->default_str(declaration.text(*settings));
    option->type_name(OptionTypeName(declaration.type, declaration.choices));
    option->expected(1);
    if (declaration.required) option->required();
    for (const std::string& colmap : declaration.colmap_names) {
      app.add_option(
             "--" + colmap,
             [store, colmap, name = declaration.name](const CLI::results_t& values) {
               std::cerr << "ramap: note: --" << colmap << " read as --" << name << "\n";
               store(values.front());
               return true;
             },
             "COLMAP's name of --" + declaration.name)
          ->expected(1)
          ->group("");
    }
  }
}

// Parses argv into `app`. Returns an exit code when the process should stop now (help was asked
// for, or the options are wrong: the reason is printed), std::nullopt to go on.
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

// A command whose options are one table: `table` registered on `app` and argv parsed into
// `settings` (ParseOptions's return).
template <typename Settings>
std::optional<int> ParseCommandLine(CLI::App& app, const OptionTable<Settings>& table,
                                    Settings* settings, int argc, char** argv) {
  AddOptionTable(app, table, settings);
  return ParseOptions(app, argc, argv);
}

// --log_level of the commands that do long work: 0 prints the result alone; 1 (the default, and any
// higher level) also one line per stage and, on a terminal, a progress line redrawn in place while
// a stage works (util/progress_line.h).
template <typename Settings, typename Access>
OptionDeclaration<Settings> LogLevelOption(Access access) {
  return NumberOption<Settings>(
      "log_level", access, AtLeast(0),
      "0: the result alone; 1: one line per stage, and a progress line on a terminal");
}

// A file or folder a command reads or writes: an empty text names none and is refused.
template <typename Settings, typename Access>
OptionDeclaration<Settings> PathOption(std::string name, Access access, std::string help) {
  return AlsoChecked(TextOption<Settings>(std::move(name), access, std::move(help)),
                     [](const std::string& text) -> std::string {
                       return text.empty() ? "names no file or folder (the path is empty)" : "";
                     });
}

// --output_type of the commands that write a COLMAP model: BIN or TXT (either case).
template <typename Settings, typename Access>
OptionDeclaration<Settings> ModelFormatOption(Access access) {
  OptionDeclaration<Settings> d;
  d.name = "output_type";
  d.type = OptionType::kText;
  d.help = "BIN or TXT";
  d.check = [](const std::string& text) -> std::string {
    try {
      ModelFormatFromName(text, "--output_type");
    } catch (const InputError&) {
      return "'" + text + "' is not BIN or TXT";
    }
    return "";
  };
  d.text = [access](const Settings& s) -> std::string {
    return access(s) == ModelFormat::kText ? "TXT" : "BIN";
  };
  d.store = [access](Settings& s, const std::string& text) {
    access(s) = ModelFormatFromName(text, "--output_type");
  };
  return d;
}

// Where a command's progress lines go at `log_level`: std::cout, or nowhere at 0.
inline std::ostream* ProgressStream(int log_level) { return log_level > 0 ? &std::cout : nullptr; }

}  // namespace ramap::cli
