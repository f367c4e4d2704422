#include "ramap/util/output_policy.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "ramap/util/error.h"

namespace ramap {
namespace fs = std::filesystem;

namespace {

// What a model folder written by ramap or COLMAP holds (COLMAP's mapper adds project.ini).
const std::array<const char*, 14> kModelFiles = {
    "cameras.bin",  "images.bin", "points3D.bin",    "cameras.txt",        "images.txt",
    "points3D.txt", "rigs.bin",   "frames.bin",      "trajectory_tum.txt", "geo_origin.txt",
    "rigs.txt",     "frames.txt", "cameras.geojson", "project.ini"};

bool IsModelFileName(const std::string& name) {
  return std::any_of(kModelFiles.begin(), kModelFiles.end(),
                     [&](const char* file) { return name == file; });
}

bool SameFile(const std::string& a, const std::string& b) {
  std::error_code ec;
  return fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec) && !ec;
}

std::string Named(const std::string& option, const std::string& path) {
  return option + " " + path;
}

// The nearest folder at or above `start` that exists: where an output that may not exist yet
// would be created. Throws InputError naming the option when a file stands in the way, or when
// that folder cannot be written (caught here, before any work, instead of as a filesystem error
// after it).
void CheckWritablePlace(const std::string& option, const std::string& path, fs::path start) {
  std::error_code ec;
  if (start.empty()) start = ".";
  while (!fs::exists(start, ec)) {
    const fs::path parent = start.parent_path();
    start = parent.empty() || parent == start ? fs::path(".") : parent;
    if (start == ".") break;
  }
  if (!fs::is_directory(start, ec)) {
    throw InputError(Named(option, path),
                     "cannot be created: " + start.string() + " is a file, not a folder");
  }
  if (::access(start.c_str(), W_OK | X_OK) != 0) {
    throw InputError(
        Named(option, path),
        "cannot be written: no permission to create or change files in " + start.string());
  }
  // Permission bits do not tell everything (root, a read-only mount, /sys): a folder made and
  // removed again does.
  const fs::path probe = start / (".ramap-probe-" + std::to_string(::getpid()));
  const bool made = fs::create_directory(probe, ec);
  if (ec) {
    throw InputError(Named(option, path), "cannot be written: creating files in " + start.string() +
                                              " fails (" + ec.message() + ")");
  }
  if (made) fs::remove(probe, ec);
}

}  // namespace

void CheckFileOutput(const std::string& option, const std::string& path,
                     const std::vector<std::string>& inputs) {
  if (path.empty()) throw InputError(option, "is empty; give a file path");
  const fs::path as_path(path);
  std::error_code ec;
  if (!as_path.has_filename() || as_path.filename() == "." || as_path.filename() == "..") {
    throw InputError(Named(option, path), "names a folder; give a file path");
  }
  if (fs::is_directory(path, ec)) {
    throw InputError(Named(option, path),
                     "is a folder; ramap writes a file here and never replaces a folder");
  }
  CheckWritablePlace(option, path, as_path.parent_path());
  for (const std::string& input : inputs) {
    if (input.empty()) continue;
    // A model folder given as input is read file by file: its model files are inputs too.
    const bool in_input_model =
        fs::is_directory(input, ec) &&
        SameFile(as_path.parent_path().empty() ? "." : as_path.parent_path().string(), input) &&
        IsModelFileName(as_path.filename().string());
    if (SameFile(path, input) || in_input_model) {
      throw InputError(Named(option, path),
                       "is an input of this run (" + input + "); ramap never overwrites its input");
    }
  }
}

void CheckFolderOutput(const std::string& option, const std::string& path,
                       const std::vector<std::string>& inputs) {
  if (path.empty()) throw InputError(option, "is empty; give a folder path");
  std::error_code ec;
  if (fs::exists(path, ec) && !fs::is_directory(path, ec)) {
    throw InputError(Named(option, path), "exists and is not a folder");
  }
  CheckWritablePlace(option, path, path);
  for (const std::string& input : inputs) {
    if (!input.empty() && SameFile(path, input)) {
      throw InputError(Named(option, path), "is an input of this run (" + input +
                                                "); write the output to another folder");
    }
  }
}

void CheckModelOutputMayReplaceInput(const std::string& option, const std::string& path,
                                     const std::string& input_model,
                                     const std::vector<std::string>& other_inputs) {
  if (!path.empty() && SameFile(path, input_model)) {
    CheckFolderOutput(option, path, other_inputs);
    return;
  }
  std::vector<std::string> inputs = other_inputs;
  inputs.push_back(input_model);
  CheckFolderOutput(option, path, inputs);
}

void CheckNewDatabasePath(const std::string& option, const std::string& path,
                          const std::vector<std::string>& inputs) {
  CheckFileOutput(option, path, inputs);
  std::error_code ec;
  if (fs::exists(fs::symlink_status(path, ec))) {
    throw InputError(Named(option, path),
                     "exists already; ramap writes a new database and never overwrites one "
                     "(remove it, or choose another path)");
  }
}

namespace {

// The first entry of `folder` that `owned(entry, &inner)` does not accept (`inner`, when it names
// something deeper, else the entry), the folder itself when it cannot be listed; empty when every
// entry is accepted.
template <typename Owned>
std::string FirstForeignEntry(const std::string& folder, Owned&& owned) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return folder;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) {
    std::string inner;
    if (!owned(entry, &inner)) return inner.empty() ? entry.path().string() : inner;
  }
  return ec ? folder : "";
}

bool NoneForeign(const std::string& found, std::string* foreign) {
  if (!found.empty() && foreign != nullptr) *foreign = found;
  return found.empty();
}

}  // namespace

bool IsReplaceableModelFolder(const std::string& folder, std::string* foreign) {
  return NoneForeign(FirstForeignEntry(folder,
                                       [](const fs::directory_entry& entry, std::string*) {
                                         std::error_code ec;
                                         return IsModelFileName(entry.path().filename().string()) &&
                                                entry.is_regular_file(ec);
                                       }),
                     foreign);
}

bool IsRamapReport(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(512, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return head.find("<meta name=\"generator\" content=\"ramap\">") != std::string::npos;
}

bool IsReplaceableMapperOutput(const std::string& folder, std::string* foreign) {
  return NoneForeign(
      FirstForeignEntry(folder,
                        [](const fs::directory_entry& entry, std::string* inner) {
                          const std::string name = entry.path().filename().string();
                          std::error_code ec;
                          if (name == "summary.json" || name == "project.ini") {
                            return entry.is_regular_file(ec);
                          }
                          if (name == "report.html") {
                            return entry.is_regular_file(ec) &&
                                   IsRamapReport(entry.path().string());
                          }
                          const bool numbered =
                              !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
                                return c >= '0' && c <= '9';
                              });
                          return numbered && IsReplaceableModelFolder(entry.path().string(), inner);
                        }),
      foreign);
}

}  // namespace ramap
