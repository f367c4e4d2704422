// `ramap <command> [--option value ...]`: dispatch to a subcommand, report errors uniformly.
#include <glog/logging.h>

#include <CLI/CLI.hpp>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "commands.h"
#include "ramap/util/allocator.h"
#include "ramap/util/error.h"
#include "ramap/util/staged_output.h"
#include "ramap_version.h"

namespace {

void PrintUsage(std::ostream& out) {
  out << "ramap: structure from motion by motion averaging, COLMAP in and out.\n\n"
         "Usage: ramap <command> [--option value ...]\n"
         "       ramap <command> -h   (options of one command)\n"
         "       ramap --version      (version and commit)\n\nCommands:\n";
  for (const ramap::cli::Command& command : ramap::cli::AllCommands()) {
    out << "  " << command.name << std::string(22 - std::min<size_t>(20, command.name.size()), ' ')
        << command.summary << "\n";
  }
  // nerfstudio reads the version of the `colmap` it runs from the help line that starts with
  // "COLMAP"; this one tells it which command lines to send.
  out << "\nCOLMAP 3.8 and 4.x command lines are accepted: tools that run `colmap` (nerfstudio, "
         "3DGS's convert.py) can run ramap instead.\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && (!std::strcmp(argv[1], "--version") || !std::strcmp(argv[1], "version"))) {
    std::cout << "ramap " << RAMAP_VERSION << " (commit " << RAMAP_COMMIT << ")\n";
    return 0;
  }
  if (argc < 2 || !std::strcmp(argv[1], "help") || !std::strcmp(argv[1], "-h") ||
      !std::strcmp(argv[1], "--help")) {
    PrintUsage(std::cout);
    return argc < 2 ? 1 : 0;
  }
  ramap::KeepFreedMemoryForReuse();
  ramap::InstallInterruptCleanup();
  // Ceres reports a failed linear solve inside a step it then retries as a glog WARNING; the
  // solver recovers, so only errors reach the user.
  google::InitGoogleLogging(argv[0]);
  FLAGS_minloglevel = google::GLOG_ERROR;
  const std::string name = argv[1];
  for (const ramap::cli::Command& command : ramap::cli::AllCommands()) {
    if (command.name != name) continue;
    try {
      // The command sees itself as argv[0]; COLMAP's names of its options are among its
      // declarations' aliases (cli/options.h).
      return command.run(argc - 1, argv + 1);
    } catch (const ramap::InputError& error) {
      std::cerr << "ramap " << name << ": error: " << error.what() << "\n";
      return 2;
    } catch (const CLI::Error& error) {
      std::cerr << "ramap " << name << ": error: " << error.what() << "\n";
      return 2;
    } catch (const std::filesystem::filesystem_error& error) {
      // A place that became unwritable during the run (a full disk, a mount gone read-only):
      // named as the user gave it, without the staging suffix.
      std::cerr << "ramap " << name << ": error: cannot write "
                << ramap::FinalPathOf(error.path1().string()) << ": " << error.code().message()
                << "\n";
      return 2;
    } catch (const std::exception& error) {
      std::cerr << "ramap " << name << ": internal error: " << error.what() << "\n";
      return 3;
    }
  }
  std::cerr << "ramap: unknown command '" << name << "'\n\n";
  PrintUsage(std::cerr);
  return 1;
}
