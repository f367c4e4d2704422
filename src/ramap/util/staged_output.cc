#include "ramap/util/staged_output.h"

#include <atomic>
#include <filesystem>
#include <fstream>
#include <system_error>

#include <unistd.h>

#include "ramap/util/error.h"

namespace ramap {
namespace fs = std::filesystem;

namespace {

std::string MakeStagingName(const std::string& final_path) {
  static std::atomic<int> counter{0};
  fs::path path(final_path);
  // Strip a trailing separator so that "out/" stages as "out.ramap-tmp-..." beside it.
  if (!path.has_filename()) path = path.parent_path();
  return path.string() + ".ramap-tmp-" + std::to_string(::getpid()) + "-" +
         std::to_string(counter++);
}

}  // namespace

StagedPath::StagedPath(std::string final_path)
    : final_path_(std::move(final_path)), staging_path_(MakeStagingName(final_path_)) {
  std::error_code ec;
  fs::remove_all(staging_path_, ec);
}

StagedPath::~StagedPath() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(staging_path_, ec);
}

void StagedPath::Commit() {
  std::error_code ec;
  fs::path target(final_path_);
  if (!target.has_filename()) target = target.parent_path();
  if (fs::exists(target, ec)) fs::remove_all(target, ec);
  if (ec) throw InputError(final_path_, "cannot replace the existing output: " + ec.message());
  fs::rename(staging_path_, target, ec);
  if (ec) throw InputError(final_path_, "cannot move the finished output into place: " + ec.message());
  committed_ = true;
}

void WriteFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                         bool binary) {
  StagedPath staged(path);
  {
    std::ofstream file(staged.path(), binary ? std::ios::binary | std::ios::out : std::ios::out);
    if (!file) throw InputError(path, "cannot open for writing");
    write(file);
    file.flush();
    if (!file) throw InputError(path, "write failed (disk full?)");
  }
  staged.Commit();
}

}  // namespace ramap
