// Image lists as COLMAP's --image_list_path reads them: one image name per line, relative to the
// image folder.
#pragma once

#include <string>
#include <vector>

namespace ramap {

// The names of the list at `path`, trimmed of surrounding blanks; empty lines and lines starting
// with '#' are skipped. Throws InputError naming `path` when it cannot be opened or names nothing.
std::vector<std::string> ReadImageList(const std::string& path);

}  // namespace ramap
