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
  // Moves what was written at path() to final_path(). A file there is replaced; a folder never is
  // (an empty one excepted): that throws InputError and leaves the staged output to the destructor.
  void Commit();

 private:
  std::string final_path_;
  std::string staging_path_;
  bool committed_ = false;
};

// A path a command creates directly (a database it fills in place, an output folder): removed
// again when the guard is destroyed before Keep(), on an error or an interrupt, but only when it
// did not exist before the guard was made.
class CreatedOutput {
 public:
  explicit CreatedOutput(std::string path);
  ~CreatedOutput();
  CreatedOutput(const CreatedOutput&) = delete;
  CreatedOutput& operator=(const CreatedOutput&) = delete;
  void Keep();

 private:
  std::string path_;
  bool created_ = false;
  bool kept_ = false;
};

// The final path a staged path stands for (for a path inside a staged folder, that folder's),
// as the caller named it; any other path unchanged. Names an output in an error message.
std::string FinalPathOf(const std::string& path);

// On SIGINT, SIGTERM or SIGHUP, every staged path and every CreatedOutput not yet kept is removed
// and the process exits with 128 + the signal, whichever thread the signal reaches. Call once from
// main().
void InstallInterruptCleanup();
// Removes every staged path and CreatedOutput not yet kept (what an interrupt does).
void RemoveLiveOutputs();

// Writes one file through `write` and renames it into place; throws InputError naming the path
// when the file cannot be written.
void WriteFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                         bool binary = false);

}  // namespace ramap
