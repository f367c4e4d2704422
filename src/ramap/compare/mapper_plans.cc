#include "ramap/compare/mapper_plans.h"

#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <regex>

#include "ramap/io/colmap_database.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

// A COLMAP mapper on `database_path`: `subcommand` "mapper" (incremental, whose options 3.8 and 4
// share, in section "Mapper") or "global_mapper" (GLOMAP, section "GlobalMapper").
std::string ColmapMapperCommand(const std::string& binary, const std::string& subcommand,
                                const std::string& section, const std::string& database_path,
                                const std::string& output_folder, const CompareOptions& options) {
  std::string command = ShellQuote(binary) + " " + subcommand + " --database_path " +
                        ShellQuote(database_path) + " --image_path " +
                        ShellQuote(options.image_path) + " --output_path " +
                        ShellQuote(output_folder) + " --" + section + ".num_threads " +
                        std::to_string(options.num_threads);
  if (!options.refine_intrinsics) {
    for (const char* what : {"focal_length", "principal_point", "extra_params"}) {
      command += " --" + section + ".ba_refine_" + what + " 0";
    }
  }
  return command;
}

std::string RamapMapperCommand(const std::string& binary, const std::string& output_folder,
                               const CompareOptions& options, bool refine) {
  std::string command =
      ShellQuote(binary) + " mapper --database_path " + ShellQuote(options.database_path) +
      " --output_path " + ShellQuote(output_folder) + " --Mapper.num_threads " +
      std::to_string(options.num_threads) + " --Mapper.refine " + (refine ? "1" : "0");
  // Without --Mapper.refine the subset's adjustment (Mapper.subset_adjustment) refines too.
  if (!options.refine_intrinsics) {
    command +=
        " --BundleAdjustment.refine_focal_length 0 --BundleAdjustment.refine_principal_point 0"
        " --BundleAdjustment.refine_extra_params 0";
  }
  return command;
}

}  // namespace

std::string ShellQuote(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string ColmapVersion(const std::string& colmap_binary) {
  const std::string command = ShellQuote(colmap_binary) + " help 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  std::string help;
  if (pipe) {
    std::array<char, 512> buffer;
    while (help.size() < 4096 && fgets(buffer.data(), buffer.size(), pipe.get()) != nullptr) {
      help += buffer.data();
    }
  }
  std::smatch match;
  if (std::regex_search(help, match, std::regex("COLMAP ([0-9]+(\\.[0-9]+)*)"))) return match[1];
  return "peer";
}

std::vector<MapperPlan> MapperPlans(const CompareOptions& options,
                                    const std::string& peer_version) {
  const std::string ramap = options.ramap_binary.empty()
                                ? fs::read_symlink("/proc/self/exe").string()
                                : options.ramap_binary;
  auto folder_path = [&](const std::string& folder) { return options.output_path + "/" + folder; };
  std::vector<MapperPlan> plans;
  // COLMAP 3.8 maps a database of a later generation from a 3.8 copy of it.
  const bool needs_38_copy =
      ReadDatabaseGeneration(options.database_path) != DatabaseGeneration::kColmap38;
  const std::string colmap_database =
      needs_38_copy ? folder_path("colmap.database.db") : options.database_path;
  plans.push_back({mapper_row::kColmap, "colmap",
                   ColmapMapperCommand(options.colmap_binary, "mapper", "Mapper", colmap_database,
                                       folder_path("colmap"), options),
                   colmap_database, needs_38_copy, needs_38_copy});
  if (!options.peer_colmap_binary.empty()) {
    // Each peer gets its own copy: COLMAP 4 upgrades a 3.8 database when it opens it.
    const std::string incremental_copy = folder_path("colmap_peer.database.db");
    plans.push_back({std::string(mapper_row::kColmap) + " " + peer_version, "colmap_peer",
                     ColmapMapperCommand(options.peer_colmap_binary, "mapper", "Mapper",
                                         incremental_copy, folder_path("colmap_peer"), options),
                     incremental_copy, true});
    const std::string global_copy = folder_path("glomap.database.db");
    plans.push_back(
        {mapper_row::kGlomap, "glomap",
         ColmapMapperCommand(options.peer_colmap_binary, "global_mapper", "GlobalMapper",
                             global_copy, folder_path("glomap"), options),
         global_copy, true});
  }
  plans.push_back({mapper_row::kRamap, "ramap",
                   RamapMapperCommand(ramap, folder_path("ramap"), options, false),
                   options.database_path, false});
  plans.push_back({mapper_row::kRamapBa, "ramap_ba",
                   RamapMapperCommand(ramap, folder_path("ramap_ba"), options, true),
                   options.database_path, false});
  return plans;
}

}  // namespace ramap
