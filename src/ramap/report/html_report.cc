#include "ramap/report/html_report.h"

#include <ctime>
#include <string>
#include <utility>
#include <vector>

#include "ramap/util/error.h"
#include "ramap/util/staged_output.h"
#include "ramap_version.h"

namespace ramap {
namespace report_assets {
// Compiled in from report/assets by cmake/embed_assets.cmake.
extern const char kPage[];
extern const char kStyle[];
extern const char kScript[];
extern const char kThreeBundle[];
extern const char kThreeLicense[];
}  // namespace report_assets

namespace {

// The data as a JSON text that is safe inside a <script> element: every "<" written as the JSON
// escape \u003c (the same string to JSON), so that no "</script>" or "<!--" in an image name or
// path can end the element early.
std::string ScriptSafeJson(const nlohmann::json& data) {
  const std::string text = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string safe;
  safe.reserve(text.size());
  for (const char c : text) {
    if (c == '<') {
      safe += "\\u003c";
    } else {
      safe += c;
    }
  }
  return safe;
}

std::string HtmlEscaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// The page with each /*@NAME@*/ marker of the template replaced once, in one pass over the
// template (a marker's text inside an inserted part is left alone).
std::string FillTemplate(const std::string& page,
                         const std::vector<std::pair<std::string, std::string>>& parts) {
  std::string out;
  size_t position = 0;
  while (true) {
    size_t next = std::string::npos;
    const std::pair<std::string, std::string>* part = nullptr;
    for (const auto& candidate : parts) {
      const size_t at = page.find(candidate.first, position);
      if (at < next) {
        next = at;
        part = &candidate;
      }
    }
    if (part == nullptr) break;
    out.append(page, position, next - position);
    out += part->second;
    position = next + part->first.size();
  }
  out.append(page, position, std::string::npos);
  return out;
}

// "ramap 0.1.0 (commit 1a2b3c4d5e), 2026-12-05 12:00 UTC": who wrote the page, and when.
std::string WrittenBy() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char when[32];
  std::strftime(when, sizeof(when), "%Y-%m-%d %H:%M UTC", &utc);
  return std::string("ramap ") + RAMAP_VERSION + " (commit " + RAMAP_COMMIT + "), " + when;
}

}  // namespace

std::string RenderHtmlReport(const nlohmann::json& given) {
  nlohmann::json data = given;
  data["written_by"] = WrittenBy();
  const std::string title = data.value("title", std::string("ramap report"));
  return FillTemplate(report_assets::kPage, {{"/*@TITLE@*/", HtmlEscaped(title)},
                                             {"/*@STYLE@*/", report_assets::kStyle},
                                             {"/*@DATA@*/", ScriptSafeJson(data)},
                                             {"/*@THREE@*/", report_assets::kThreeBundle},
                                             {"/*@THREE_LICENSE@*/", report_assets::kThreeLicense},
                                             {"/*@SCRIPT@*/", report_assets::kScript}});
}

void WriteHtmlReport(const nlohmann::json& data, const std::string& path) {
  const std::string page = RenderHtmlReport(data);
  WriteFileAtomically(path, [&](std::ostream& out) { out << page; });
}

}  // namespace ramap
