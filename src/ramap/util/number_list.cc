#include "ramap/util/number_list.h"

#include <sstream>
#include <stdexcept>

#include "ramap/util/error.h"

namespace ramap {

std::vector<double> ParseNumberList(const std::string& text, const std::string& option) {
  std::vector<double> numbers;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      size_t used = 0;
      numbers.push_back(std::stod(item, &used));
      if (item.find_first_not_of(' ', used) != std::string::npos) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw InputError(option, "'" + item + "' is not a number");
    }
  }
  return numbers;
}

}  // namespace ramap
