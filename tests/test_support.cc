#include "test_support.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <sys/wait.h>

namespace ramap::test {
namespace fs = std::filesystem;

std::string SharedDataDir() {
  if (const char* env = std::getenv("RAMAP_DATA_DIR"); env != nullptr && *env != '\0') return env;
  return RAMAP_SHARED_DATA_DIR;
}

std::string SharedDataPath(const std::string& relative) {
  const fs::path path = fs::path(SharedDataDir()) / relative;
  return fs::exists(path) ? path.string() : std::string();
}

bool ColmapAvailable() {
  static const bool available = RunCommand("command -v colmap").exit_code == 0;
  return available;
}

std::string RamapBinary() { return RAMAP_CLI_PATH; }

CommandResult RunCommand(const std::string& command_line) {
  CommandResult result;
  const std::string full = command_line + " 2>&1";
  FILE* pipe = popen(full.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

TempDir::TempDir() {
  std::string pattern = (fs::temp_directory_path() / "ramap-test-XXXXXX").string();
  path_ = mkdtemp(pattern.data());
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

}  // namespace ramap::test
