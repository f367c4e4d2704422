// libFuzzer harness: a pose prior file (NAME V1 V2 V3 [SX SY SZ]) of arbitrary bytes.
#include "fuzz_input.h"
#include "ramap/io/pose_prior_file.h"

RAMAP_FUZZ_FILE_READER(ramap::ReadPriorFile)
