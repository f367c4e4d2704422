// Output that appears whole or not at all: files and folders are written under a temporary name
// beside their final path and renamed into place only when the writer commits. A writer that
// throws (or is destroyed without committing) leaves nothing behind.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace ramap {

// A temporary path beside `final_path`; Commit() renames it over `final_path`.
// Works for a file or a folder (the caller creates what it needs at path()).
class StagedPath {
 public:
  explicit StagedPath(std::string final_path);
  ~StagedPath();
  StagedPath(const StagedPath&) = delete;
  StagedPath& operator=(const StagedPath&) = delete;

  // Where to write now.
  const std::string& path() const { return staging_path_; }
  const std::string& final_path() const { return final_path_; }
  // Replaces whatever is at final_path() with what was written at path().
  void Commit();

 private:
  std::string final_path_;
  std::string staging_path_;
  bool committed_ = false;
};

// Writes one file through `write` and renames it into place; throws InputError naming the path
// when the file cannot be written.
void WriteFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                         bool binary = false);

}  // namespace ramap
