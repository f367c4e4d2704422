// libFuzzer harness: ground-truth and trajectory files (TUM, KITTI, Middlebury, Strecha's .camera,
// chosen by the first byte), then matched to image names as evaluate does.
#include <vector>

#include "fuzz_input.h"
#include "ramap/io/trajectory.h"
#include "ramap/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  using ramap::GroundTruthFormat;
  const GroundTruthFormat formats[4] = {GroundTruthFormat::kTum, GroundTruthFormat::kKitti,
                                        GroundTruthFormat::kMiddlebury,
                                        GroundTruthFormat::kStrecha};
  const GroundTruthFormat format = formats[data[0] % 4];
  std::string path;
  if (format == GroundTruthFormat::kStrecha) {
    path = ramap::fuzz::ScratchDir() + "/strecha";
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
    std::ofstream(path + "/0000.png.camera", std::ios::binary)
        << std::string(reinterpret_cast<const char*>(data + 1), size - 1);
  } else {
    path = ramap::fuzz::WriteScratchFile("trajectory.txt", data + 1, size - 1);
  }
  try {
    const ramap::GroundTruth truth = ramap::ReadGroundTruth(path, format);
    ramap::GroundTruthByImageName(truth, {"000000.png", "000001.png", "0000.png", "a.png"});
  } catch (const ramap::InputError&) {
  }
  return 0;
}
