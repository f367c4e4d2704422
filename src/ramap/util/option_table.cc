#include "ramap/util/option_table.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace ramap {

bool OptionRange::Contains(double value) const {
  return std::isfinite(value) && (low_open ? value > low : value >= low) &&
         (high_open ? value < high : value <= high);
}

std::string OptionRange::Describe() const {
  std::string out = "a finite number";
  if (std::isfinite(low)) out += std::string(low_open ? " > " : " >= ") + FormatOptionNumber(low);
  if (std::isfinite(high)) {
    out += std::string(std::isfinite(low) ? " and" : "") + (high_open ? " < " : " <= ") +
           FormatOptionNumber(high);
  }
  return out;
}

OptionRange AtLeast(double low, double high) { return {low, false, high, false}; }
OptionRange Above(double low, double high) { return {low, true, high, true}; }
OptionRange AnyNumber() { return {}; }

std::string FormatOptionNumber(double value) {
  char buffer[32];
  if (value == std::floor(value) && std::fabs(value) < 1e15) {
    std::snprintf(buffer, sizeof(buffer), "%.0f", value);
    return buffer;
  }
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof(buffer), "%.*g", precision, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

namespace {

// Whole-text conversions: "12abc" and "" are not numbers.
bool ParseNumber(const std::string& text, double* value) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

bool ParseInteger(const std::string& text, long long* value) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
  char* end = nullptr;
  errno = 0;
  *value = std::strtoll(text.c_str(), &end, 10);
  return errno == 0 && end == text.c_str() + text.size();
}

std::string JoinWords(const std::vector<std::string>& words, const std::string& last_joiner) {
  std::string out;
  for (size_t i = 0; i < words.size(); ++i) {
    if (i > 0) out += i + 1 == words.size() ? last_joiner : ", ";
    out += words[i];
  }
  return out;
}

std::string Lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace

bool OptionBoolValue(const std::string& text) {
  const std::string word = Lower(text);
  return word == "1" || word == "true" || word == "on" || word == "yes" || word == "enable" ||
         word == "t" || word == "y";
}

std::string OptionValueProblem(OptionType type, const OptionRange& range,
                               const std::vector<std::string>& choices, const std::string& text) {
  switch (type) {
    case OptionType::kBool: {
      static const std::vector<std::string> words = {"0",   "1",   "true", "false",  "on",
                                                     "off", "yes", "no",   "enable", "disable",
                                                     "t",   "f",   "y",    "n"};
      if (std::find(words.begin(), words.end(), Lower(text)) != words.end()) return "";
      return "'" + text + "' is not 1 or 0";
    }
    case OptionType::kText:
      return "";
    case OptionType::kChoice:
      if (std::find(choices.begin(), choices.end(), text) != choices.end()) return "";
      return "'" + text + "' is not " + JoinWords(choices, " or ");
    case OptionType::kInteger: {
      long long value = 0;
      if (!ParseInteger(text, &value)) return "'" + text + "' is not an integer";
      if (!range.Contains(static_cast<double>(value))) {
        return "must be " + range.Describe() + ", got " + text;
      }
      return "";
    }
    case OptionType::kNumber: {
      double value = 0;
      if (!ParseNumber(text, &value)) return "'" + text + "' is not a number";
      if (!range.Contains(value)) return "must be " + range.Describe() + ", got " + text;
      return "";
    }
  }
  return "";
}

std::string UnknownOptionMessage(const std::string& name, const std::vector<std::string>& known) {
  std::string message = "no such option";
  size_t best_distance = std::max<size_t>(3, name.size() / 4) + 1;
  std::string best;
  for (const std::string& candidate : known) {
    const size_t distance = EditDistance(name, candidate);
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  if (!best.empty()) message += " (did you mean --" + best + "?)";
  return message;
}

std::string OptionValueHint(OptionType type, const OptionRange& range,
                            const std::vector<std::string>& choices) {
  switch (type) {
    case OptionType::kBool:
      return "0 or 1";
    case OptionType::kText:  // choices, when given, are the usual values of a checked text
      return choices.empty() ? "text" : JoinWords(choices, " or ") + " (or a COLMAP version)";
    case OptionType::kChoice:
      return JoinWords(choices, " or ");
    case OptionType::kInteger:
    case OptionType::kNumber: {
      std::string hint = type == OptionType::kInteger ? "integer" : "number";
      const std::string bounds = range.Describe().substr(std::string("a finite number").size());
      return hint + bounds;
    }
  }
  return "";
}

std::string OptionTypeName(OptionType type, const std::vector<std::string>& choices) {
  switch (type) {
    case OptionType::kBool:
      return "0|1";
    case OptionType::kText:
      return "TEXT";
    case OptionType::kInteger:
      return "INT";
    case OptionType::kNumber:
      return "FLOAT";
    case OptionType::kChoice: {
      std::string out;
      for (const std::string& choice : choices) out += (out.empty() ? "" : "|") + choice;
      return out;
    }
  }
  return "";
}

}  // namespace ramap
