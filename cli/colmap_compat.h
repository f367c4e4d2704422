// COLMAP's command-line names where they differ from ramap's, so that ramap stands in for the
// `colmap` executable in the command lines other tools issue (nerfstudio's ns-process-data, 3D
// Gaussian Splatting's convert.py, hloc's and users' scripts), under COLMAP 3.x and 4.x names:
//  - renamed options are read as ramap's (--SiftExtraction.max_image_size and COLMAP 4's
//    --FeatureExtraction.max_image_size; --SiftMatching.* and --FeatureMatching.*;
//    --Mapper.ba_* as --BundleAdjustment.*; --SequentialMatching.overlap);
//  - options that ask for a GPU are accepted and dropped with a note: ramap runs on the CPU;
//  - any other option is left to the command, which refuses one it does not know, by name.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace ramap::cli {

// `args` (the options after the command name, as given) with COLMAP's names rewritten; a note per
// rewritten or dropped option goes to `notes`. Both "--name value" and "--name=value" are read.
std::vector<std::string> TranslateColmapOptions(const std::vector<std::string>& args,
                                                std::ostream& notes);

}  // namespace ramap::cli
