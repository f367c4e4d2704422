// Lists of numbers as options take them: "a,b,c" (COLMAP's --ImageReader.camera_params style).
#pragma once

#include <string>
#include <vector>

namespace ramap {

// The numbers of "a,b,c,..." (spaces around an item allowed); throws InputError naming `option`
// for an item that is not a number. An empty text gives no numbers.
std::vector<double> ParseNumberList(const std::string& text, const std::string& option);

}  // namespace ramap
