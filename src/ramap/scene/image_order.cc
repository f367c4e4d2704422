#include "ramap/scene/image_order.h"

#include <algorithm>
#include <cctype>
#include <numeric>
#include <set>

namespace ramap {
namespace {

// "frame_000123.png" -> ("frame_", 123, true); names without a trailing number give false.
struct NameKey {
  std::string prefix;
  long long number = 0;
  bool has_number = false;
};

NameKey SplitName(const std::string& name) {
  const std::string stem = name.substr(0, name.find_last_of('.'));
  size_t digits = stem.size();
  while (digits > 0 && std::isdigit(static_cast<unsigned char>(stem[digits - 1]))) --digits;
  NameKey key;
  key.prefix = stem.substr(0, digits);
  // Longer digit runs would overflow; such names are ordered by name.
  if (digits < stem.size() && stem.size() - digits < 18) {
    key.number = std::stoll(stem.substr(digits));
    key.has_number = true;
  }
  return key;
}

}  // namespace

std::vector<size_t> CaptureOrder(const std::vector<std::string>& names) {
  std::vector<NameKey> keys;
  keys.reserve(names.size());
  for (const std::string& name : names) keys.push_back(SplitName(name));
  std::vector<size_t> order(names.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    if (keys[a].prefix != keys[b].prefix) return keys[a].prefix < keys[b].prefix;
    if (keys[a].number != keys[b].number) return keys[a].number < keys[b].number;
    return names[a] < names[b];
  });
  return order;
}

bool IsSequentialInput(InputOrder order, const std::vector<std::string>& names) {
  return order == InputOrder::kSequential || (order == InputOrder::kAuto && LooksSequential(names));
}

bool LooksSequential(const std::vector<std::string>& names) {
  std::set<std::string> prefixes;
  for (const std::string& name : names) {
    const NameKey key = SplitName(name);
    if (!key.has_number) return false;
    prefixes.insert(key.prefix);
  }
  return prefixes.size() == 1;
}

std::vector<uint32_t> ImageIdsInCaptureOrder(const FeatureDatabase& database) {
  std::vector<uint32_t> ids;
  std::vector<std::string> names;
  for (const auto& [id, image] : database.images) {
    ids.push_back(id);
    names.push_back(image.name);
  }
  std::vector<uint32_t> ordered;
  for (const size_t k : CaptureOrder(names)) ordered.push_back(ids[k]);
  return ordered;
}

}  // namespace ramap
