#include "ramap/util/image_codecs.h"

#include <dlfcn.h>

#include <filesystem>
#include <mutex>
#include <stdexcept>

namespace ramap {
namespace {

namespace fs = std::filesystem;

constexpr const char* kPluginName = "libramap_image_codecs.so";

// The plug-in's entry points (extern "C", so that they are found by name; same compiler and
// OpenCV on both sides).
struct ImageCodecs {
  bool (*read)(const char* path, int flags, cv::Mat* image) = nullptr;
  bool (*encode)(const char* extension, const cv::Mat* image, std::vector<uchar>* bytes) = nullptr;
};

// Where the plug-in is looked for: beside the binary or Python module holding this code (the build
// tree's ramap and ramap_tests, an installed package), then the build tree it was built in.
std::vector<fs::path> PluginCandidates() {
  std::vector<fs::path> candidates;
  Dl_info info;
  if (dladdr(reinterpret_cast<void*>(&PluginCandidates), &info) != 0 && info.dli_fname != nullptr) {
    std::error_code error;
    const fs::path self = fs::canonical(info.dli_fname, error);
    if (!error) candidates.push_back(self.parent_path() / kPluginName);
  }
#ifdef RAMAP_IMAGE_CODECS_BUILD_DIR
  const fs::path built = fs::path(RAMAP_IMAGE_CODECS_BUILD_DIR) / kPluginName;
  if (candidates.empty() || candidates.front() != built) candidates.push_back(built);
#endif
  return candidates;
}

ImageCodecs LoadImageCodecs() {
  std::string problems;
  for (const fs::path& candidate : PluginCandidates()) {
    if (!fs::exists(candidate)) {
      problems += "; " + candidate.string() + ": no such file";
      continue;
    }
    // Never unloaded: OpenCV's codecs keep static state for the life of the process.
    void* plugin = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (plugin == nullptr) {
      problems += std::string("; ") + dlerror();
      continue;
    }
    ImageCodecs codecs;
    codecs.read = reinterpret_cast<decltype(codecs.read)>(dlsym(plugin, "ramap_read_image"));
    codecs.encode = reinterpret_cast<decltype(codecs.encode)>(dlsym(plugin, "ramap_encode_image"));
    if (codecs.read != nullptr && codecs.encode != nullptr) return codecs;
    problems += "; " + candidate.string() + " lacks its entry points";
  }
  throw std::runtime_error(std::string("cannot load ramap's image codecs (") + kPluginName +
                           ", built beside the ramap binary; rebuild ramap)" + problems);
}

const ImageCodecs& Codecs() {
  static std::once_flag once;
  static ImageCodecs codecs;
  std::call_once(once, [] { codecs = LoadImageCodecs(); });
  return codecs;
}

}  // namespace

cv::Mat ReadImageFile(const std::string& path, int flags) {
  cv::Mat image;
  if (!Codecs().read(path.c_str(), flags, &image)) return cv::Mat();
  return image;
}

bool EncodeImage(const std::string& extension, const cv::Mat& image, std::vector<uchar>* bytes) {
  return Codecs().encode(extension.c_str(), &image, bytes);
}

}  // namespace ramap
