// libFuzzer harness: a COLMAP model folder in the binary format, its files
// (cameras, images, points3D, and COLMAP 4's rigs and frames when there are five parts) separated
// in the input by "\n@@\n".
#include "fuzz_input.h"
#include "ramap/io/colmap_model.h"
#include "ramap/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string folder = ramap::fuzz::WriteModelFolder(data, size, ".bin");
  try {
    ramap::ReadColmapModel(folder);
  } catch (const ramap::InputError&) {
  }
  return 0;
}
