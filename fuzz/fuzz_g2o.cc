// libFuzzer harness: a g2o pose graph of arbitrary bytes.
#include "fuzz_input.h"
#include "ramap/io/g2o_reader.h"

RAMAP_FUZZ_FILE_READER(ramap::ReadG2oRotationGraph)
