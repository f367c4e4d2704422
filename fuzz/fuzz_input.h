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

// Splits the input at the occurrences of `separator` into up to `N` parts (the model readers take
// three files, or five with COLMAP 4's rigs and frames); `count` says how many were found.
template <int N>
struct Parts {
  std::string parts[N];
  int count = 0;
};
template <int N>
inline Parts<N> Split(const uint8_t* data, size_t size, const std::string& separator) {
  Parts<N> split;
  const std::string all(reinterpret_cast<const char*>(data), size);
  size_t begin = 0;
  for (int k = 0; k < N; ++k) {
    const size_t end = k < N - 1 ? all.find(separator, begin) : std::string::npos;
    split.count = k + 1;
    if (end == std::string::npos) {
      split.parts[k] = all.substr(begin);
      break;
    }
    split.parts[k] = all.substr(begin, end - begin);
    begin = end + separator.size();
  }
  return split;
}

// The files of a model (cameras, images, points3D, and rigs and frames when the input has five
// parts, with `extension`) in a fresh folder.
inline std::string WriteModelFolder(const uint8_t* data, size_t size,
                                    const std::string& extension) {
  const std::string folder = ScratchDir() + "/model";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  const Parts<5> split = Split<5>(data, size, "\n@@\n");
  const char* names[5] = {"cameras", "images", "points3D", "rigs", "frames"};
  for (int k = 0; k < 5; ++k) {
    if (k >= 3 && k >= split.count) break;
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
