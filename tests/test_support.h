// Helpers shared by the tests: where the real data lives, temporary folders, running the ramap
// and colmap binaries.
#pragma once

#include <string>

#include <gtest/gtest.h>

namespace ramap::test {

// ../shared/data beside the checkout, or $RAMAP_DATA_DIR when set.
std::string SharedDataDir();
// SharedDataDir()/relative when it exists, else "".
std::string SharedDataPath(const std::string& relative);

// Whether the `colmap` binary is on the PATH.
bool ColmapAvailable();

// The built `ramap` binary.
std::string RamapBinary();

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};
// Runs a shell command line, capturing its output.
CommandResult RunCommand(const std::string& command_line);

// A fresh folder under the system's temporary folder, removed with its contents at scope end.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  std::string operator/(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

}  // namespace ramap::test

// Skips the current test, visibly, when a shared data set is absent; defines `var` as its path.
#define RAMAP_REQUIRE_SHARED_DATA(var, relative)                                          \
  const std::string var = ::ramap::test::SharedDataPath(relative);                        \
  if (var.empty()) {                                                                      \
    GTEST_SKIP() << "shared data '" << relative << "' not found under "                   \
                 << ::ramap::test::SharedDataDir() << " (set RAMAP_DATA_DIR)";            \
  }

// Skips the current test, visibly, when the colmap binary is not installed.
#define RAMAP_REQUIRE_COLMAP()                                                            \
  if (!::ramap::test::ColmapAvailable()) {                                                \
    GTEST_SKIP() << "colmap binary not found (scripts/install-deps.sh installs it)";      \
  }
