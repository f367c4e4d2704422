#include "ramap/compare/mapper_process.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <system_error>

#include "ramap/geometry/camera_projection.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "ramap/io/trajectory.h"
#include "ramap/mapper/stage_log.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

// Runs `command` with its output in `log_path`; returns the wall time and whether it exited 0.
std::pair<double, bool> RunTimed(const std::string& command, const std::string& log_path) {
  const auto start = std::chrono::steady_clock::now();
  const int status = std::system((command + " > " + ShellQuote(log_path) + " 2>&1").c_str());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return {seconds, status == 0};
}

// The numbered model folder under `output_path` with the most images (at least one), read once:
// its path and size go to `run`, the model is returned (none when no folder holds such a model).
std::optional<Reconstruction> ReadLargestModel(const std::string& output_path, MapperRun* run) {
  if (!fs::is_directory(output_path)) return std::nullopt;
  std::optional<Reconstruction> largest;
  for (const fs::directory_entry& entry : fs::directory_iterator(output_path)) {
    if (!entry.is_directory()) continue;
    try {
      Reconstruction model = ReadColmapModel(entry.path().string());
      ++run->num_models;
      // A model without images counts as none, as before any model is found.
      if (model.images.size() > (largest ? largest->images.size() : 0)) {
        run->model_path = entry.path().string();
        largest = std::move(model);
      }
    } catch (const InputError&) {
      // Not a model (ramap's staging folders, a half-written COLMAP snapshot).
    }
  }
  if (largest) run->num_registered = static_cast<int>(largest->images.size());
  return largest;
}

// Stage seconds from ramap's summary.json, in the order the stages ran.
std::vector<std::pair<std::string, double>> StageSeconds(const std::string& summary_path) {
  std::vector<std::pair<std::string, double>> stages;
  std::ifstream in(summary_path);
  if (!in) return stages;
  const nlohmann::json summary = nlohmann::json::parse(in, nullptr, false);
  if (summary.is_discarded() || !summary.contains("stage_seconds")) return stages;
  for (const std::string& stage : TimedMapperStages()) {
    if (summary["stage_seconds"].contains(stage)) {
      stages.push_back({stage, summary["stage_seconds"][stage].get<double>()});
    }
  }
  return stages;
}

// Stage seconds from a COLMAP log: GLOMAP's global mapper prints "<stage> done in <s> seconds"
// for each stage ("Reconstruction done in" is their sum, left out). Empty for logs without them
// (COLMAP's incremental mapper).
std::vector<std::pair<std::string, double>> LoggedStageSeconds(const std::string& log_path) {
  std::vector<std::pair<std::string, double>> stages;
  std::ifstream in(log_path);
  const std::regex done("\\] ([A-Z][A-Za-z ]*) done in ([0-9.eE+-]+) seconds");
  std::smatch match;
  for (std::string line; std::getline(in, line);) {
    if (!std::regex_search(line, match, done) || match[1] == "Reconstruction") continue;
    try {
      stages.push_back({match[1], std::stod(match[2])});
    } catch (const std::exception&) {
      // Not a number after all: the stage is left out of the figure.
    }
  }
  return stages;
}

// A peer's copy of the database, removed when the run is over (it may have been upgraded):
// byte for byte, or rewritten as a COLMAP 3.8 database.
class DatabaseCopy {
 public:
  DatabaseCopy(const std::string& from, const std::string& to, bool as_colmap38) : path_(to) {
    if (!as_colmap38) {
      fs::copy_file(from, to, fs::copy_options::overwrite_existing);
      return;
    }
    DatabaseReadOptions everything;
    everything.read_descriptors = true;
    WriteColmapDatabase(ReadColmapDatabase(from, everything), to, DatabaseGeneration::kColmap38);
  }
  ~DatabaseCopy() {
    // With the files SQLite may leave beside it.
    std::error_code ignored;
    for (const char* suffix : {"", "-wal", "-shm", "-journal"}) fs::remove(path_ + suffix, ignored);
  }
  DatabaseCopy(const DatabaseCopy&) = delete;
  DatabaseCopy& operator=(const DatabaseCopy&) = delete;

 private:
  std::string path_;
};

}  // namespace

void CheckRunFolder(const std::string& output_path, const MapperPlan& plan,
                    const std::string& database_path) {
  const std::string option = "--output_path " + output_path;
  const std::string folder = output_path + "/" + plan.folder;
  std::string foreign;
  if (fs::exists(fs::symlink_status(folder)) && !IsReplaceableMapperOutput(folder, &foreign)) {
    throw InputError(option, folder + " holds " + foreign +
                                 ", which is not an earlier compare run's output; choose another "
                                 "--output_path");
  }
  if (fs::is_directory(folder + ".log")) throw InputError(option, folder + ".log is a folder");
  if (!plan.on_database_copy) return;
  std::error_code ec;
  if (fs::is_directory(plan.database_path, ec)) {
    throw InputError(option, plan.database_path + " is a folder");
  }
  if (fs::exists(plan.database_path, ec) && fs::equivalent(plan.database_path, database_path, ec)) {
    throw InputError(
        option, plan.database_path + " is the compared database; a peer's copy would replace it");
  }
}

MapperRun RunMapperPlan(const MapperPlan& plan, const CompareOptions& options, size_t num_images,
                        Reconstruction* model) {
  const std::string folder = options.output_path + "/" + plan.folder;
  fs::remove_all(folder);
  fs::create_directories(folder);
  std::cout << "[ramap compare] " << plan.name << ": " << plan.command << std::endl;
  MapperRun run;
  run.name = plan.name;
  run.command = plan.command;
  {
    std::optional<DatabaseCopy> copy;
    if (plan.on_database_copy) {
      copy.emplace(options.database_path, plan.database_path, plan.copy_as_colmap38);
    }
    const auto [seconds, exited_cleanly] = RunTimed(plan.command, folder + ".log");
    run.seconds = seconds;
    run.succeeded = exited_cleanly;
  }
  std::optional<Reconstruction> largest = ReadLargestModel(folder, &run);
  run.succeeded = run.succeeded && largest.has_value();
  if (!run.succeeded) {
    std::cerr << "ramap compare: " << plan.name << " failed (see " << folder << ".log)\n";
  } else {
    for (const auto& [camera_id, camera] : largest->cameras) {
      run.focal_lengths_px[camera_id] = MeanFocalLength(camera);
    }
    *model = std::move(*largest);
  }
  run.stage_seconds = StageSeconds(folder + "/summary.json");
  if (run.stage_seconds.empty()) run.stage_seconds = LoggedStageSeconds(folder + ".log");
  std::cout << "[ramap compare] " << plan.name << ": " << run.num_registered << " of " << num_images
            << " images in " << run.seconds << " s" << std::endl;
  return run;
}

}  // namespace ramap
