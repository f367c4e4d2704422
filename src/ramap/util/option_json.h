// The values of a table's options as JSON, for summary.json's options block: numbers as numbers,
// switches as booleans, words as strings, each read back from the text the command line takes.
#pragma once

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "ramap/util/option_table.h"

namespace ramap {

// One option's value.
template <typename Settings>
nlohmann::json OptionJsonValue(const OptionDeclaration<Settings>& d, const Settings& settings) {
  const std::string text = d.text(settings);
  switch (d.type) {
    case OptionType::kBool:
      return text == "1";
    case OptionType::kInteger:
      return std::strtoll(text.c_str(), nullptr, 10);
    case OptionType::kNumber:
      // FormatOptionNumber's text reads back as the same double.
      return std::strtod(text.c_str(), nullptr);
    case OptionType::kChoice:
    case OptionType::kText:
      return text;
  }
  return text;
}

// {"Section": {"option": value, ...}, ...}; options without a section at the top level; COLMAP's
// ignored options left out.
template <typename Settings>
nlohmann::json OptionValuesToJson(const OptionTable<Settings>& table, const Settings& settings) {
  nlohmann::json sections = nlohmann::json::object();
  for (const OptionDeclaration<Settings>& d : table) {
    if (!d.ignored_because.empty()) continue;
    if (d.Section().empty()) {
      sections[d.name] = OptionJsonValue(d, settings);
    } else {
      sections[d.Section()][d.Key()] = OptionJsonValue(d, settings);
    }
  }
  return sections;
}

}  // namespace ramap
