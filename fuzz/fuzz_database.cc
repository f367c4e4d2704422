// libFuzzer harness: a COLMAP database (SQLite file) of arbitrary bytes, read with everything on.
#include "fuzz_input.h"
#include "ramap/io/colmap_database.h"
#include "ramap/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = ramap::fuzz::WriteScratchFile("database.db", data, size);
  std::filesystem::remove(path + "-wal");
  std::filesystem::remove(path + "-shm");
  ramap::DatabaseReadOptions options;
  options.read_descriptors = true;
  options.read_matches = true;
  try {
    ramap::ReadColmapDatabase(path, options);
  } catch (const ramap::InputError&) {
  }
  return 0;
}
