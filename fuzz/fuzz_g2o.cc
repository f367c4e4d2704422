// libFuzzer harness: a g2o file of arbitrary bytes.
#include "fuzz_input.h"
#include "ramap/io/g2o_reader.h"

RAMAP_FUZZ_FILE_READER(ramap::ReadG2oPoseGraph)
