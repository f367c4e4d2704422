#include "ramap/io/image_list.h"

#include <fstream>

#include "ramap/util/error.h"

namespace ramap {

std::vector<std::string> ReadImageList(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open the image list");
  std::vector<std::string> names;
  std::string line;
  while (std::getline(in, line)) {
    const size_t begin = line.find_first_not_of(" \t\r");
    if (begin == std::string::npos || line[begin] == '#') continue;
    names.push_back(line.substr(begin, line.find_last_not_of(" \t\r") - begin + 1));
  }
  if (names.empty()) throw InputError(path, "the image list names no image");
  return names;
}

}  // namespace ramap
