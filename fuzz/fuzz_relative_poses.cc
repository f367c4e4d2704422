// libFuzzer harness: a relative-pose file (ramap relative_poses' output) of arbitrary bytes.
#include "fuzz_input.h"
#include "ramap/io/relative_pose_file.h"

RAMAP_FUZZ_FILE_READER(ramap::ReadRelativePoses)
