// Shared by the libFuzzer harnesses: the fuzzer's bytes as files on disk (the readers take paths),
// and the one outcome a reader may have besides success, InputError. Any other exception, a
// crash or a sanitizer report is a finding.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "ramap/util/error.h"

namespace ramap::fuzz {

// A private folder for this process, emptied for each input.
inline const std::string& ScratchDir() {
  static const std::string dir = [] {
    const std::string path =
        (std::filesystem::temp_directory_path() / ("ramap-fuzz-" + std::to_string(::getpid())))
            .string();
    std::filesystem::create_directories(path);
    return path;
  }();
  return dir;
}

inline std::string WriteScratchFile(const std::string& name, const uint8_t* data, size_t size) {
  const std::string path = ScratchDir() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

// Splits the input at the first two occurrences of `separator` into up to three parts (the
// model readers take three files).
struct ThreeParts {
  std::string parts[3];
};
inline ThreeParts SplitThree(const uint8_t* data, size_t size, const std::string& separator) {
  ThreeParts split;
  const std::string all(reinterpret_cast<const char*>(data), size);
  size_t begin = 0;
  for (int k = 0; k < 3; ++k) {
    const size_t end = k < 2 ? all.find(separator, begin) : std::string::npos;
    if (end == std::string::npos) {
      split.parts[k] = all.substr(begin);
      break;
    }
    split.parts[k] = all.substr(begin, end - begin);
    begin = end + separator.size();
  }
  return split;
}

// The three files of a model (cameras, images, points3D, with `extension`) in a fresh folder.
inline std::string WriteModelFolder(const uint8_t* data, size_t size,
                                    const std::string& extension) {
  const std::string folder = ScratchDir() + "/model";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  const ThreeParts split = SplitThree(data, size, "\n@@\n");
  const char* names[3] = {"cameras", "images", "points3D"};
  for (int k = 0; k < 3; ++k) {
    std::ofstream(folder + "/" + names[k] + extension, std::ios::binary) << split.parts[k];
  }
  return folder;
}

}  // namespace ramap::fuzz

// The whole harness for a reader that takes one file's path.
#define RAMAP_FUZZ_FILE_READER(reader)                                               \
  extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {          \
    const std::string path = ramap::fuzz::WriteScratchFile("input.txt", data, size); \
    try {                                                                            \
      reader(path);                                                                  \
    } catch (const ramap::InputError&) {                                             \
    }                                                                                \
    return 0;                                                                        \
  }
