// Options declared once: each with its COLMAP-style name ("Mapper.refine"), type, default, range,
// aliases and one line of help, bound to a field of a settings struct. The command line, the
// checks, summary.json's options block (util/option_json.h), Python's keyword names and the
// options reference are all read from the declaration, so they cannot disagree. Each options
// struct owns the table of its own fields, in its own layer; a command's table assembles them
// (AppendOptions).
#pragma once

#include <algorithm>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "ramap/util/error.h"

namespace ramap {

// The values a numeric option accepts: low <= value (or <) and value <= high (or <), finite.
struct OptionRange {
  double low = -std::numeric_limits<double>::infinity();
  bool low_open = false;
  double high = std::numeric_limits<double>::infinity();
  bool high_open = false;

  bool Contains(double value) const;
  // "a finite number >= 1 and <= 256".
  std::string Describe() const;
};
// value >= low (and <= high).
OptionRange AtLeast(double low, double high = std::numeric_limits<double>::infinity());
// value > low (and < high).
OptionRange Above(double low, double high = std::numeric_limits<double>::infinity());
// Any finite number.
OptionRange AnyNumber();

enum class OptionType { kBool, kInteger, kNumber, kChoice, kText };

// One option of a settings struct `Settings`.
template <typename Settings>
struct OptionDeclaration {
  // "Section.option": --Section.option on the command line; a command's own paths and switches
  // have no section ("database_path").
  std::string name;
  // Names the option had before (README, "Renamed"): accepted as aliases of `name`.
  std::vector<std::string> former_names;
  // COLMAP's names for it (3.x and 4.x), accepted with a note that says how they are read, so
  // that command lines written for `colmap` run unchanged.
  std::vector<std::string> colmap_names;
  OptionType type = OptionType::kNumber;
  OptionRange range;                 // numeric options
  std::vector<std::string> choices;  // kChoice: the accepted words
  std::string help;
  // A command's option it cannot run without (an input path).
  bool required = false;
  // Not empty: a COLMAP option accepted and dropped, for this reason ("ramap runs on the CPU").
  std::string ignored_because;
  // A check of the text beyond type and range (empty: none): the problem, or "" when none.
  std::function<std::string(const std::string&)> check;
  // The value as the command line takes it ("1", "0.05", "adaptive").
  std::function<std::string(const Settings&)> text;
  // Stores already checked text.
  std::function<void(Settings&, const std::string&)> store;

  // "Section" of "Section.option"; "" for a name without a section.
  std::string Section() const {
    const size_t dot = name.find('.');
    return dot == std::string::npos ? "" : name.substr(0, dot);
  }
  std::string Key() const { return name.substr(name.find('.') + 1); }
  // Every name the option is accepted under: its own, its former ones, COLMAP's.
  std::vector<std::string> AllNames() const {
    std::vector<std::string> names = {name};
    names.insert(names.end(), former_names.begin(), former_names.end());
    names.insert(names.end(), colmap_names.begin(), colmap_names.end());
    return names;
  }
};

// A boolean option's value: 1, true, on, yes, enable (any case) are true; what else passes
// OptionValueProblem is false.
bool OptionBoolValue(const std::string& text);

// What is wrong with `text` as a value of an option of this type, range and choices; empty when
// nothing is ("must be a finite number >= 1, got 0", "'x' is not an integer").
std::string OptionValueProblem(OptionType type, const OptionRange& range,
                               const std::vector<std::string>& choices, const std::string& text);

// The shortest decimal text that reads back as `value` ("0.05", not "0.050000000000000003").
std::string FormatOptionNumber(double value);

// "--Foo.bar: no such option (did you mean --Foo.baz?)": the closest of `known` by edit distance,
// when one is close.
std::string UnknownOptionMessage(const std::string& name, const std::vector<std::string>& known);

// Declarations bound through `access`, a generic lambda returning a reference to the field:
// [](auto& o) -> auto& { return o.bundle_adjustment.max_num_iterations; }.
template <typename Settings, typename Access>
OptionDeclaration<Settings> BoolOption(std::string name, Access access, std::string help) {
  OptionDeclaration<Settings> d;
  d.name = std::move(name);
  d.type = OptionType::kBool;
  d.help = std::move(help);
  d.text = [access](const Settings& s) -> std::string { return access(s) ? "1" : "0"; };
  d.store = [access](Settings& s, const std::string& text) { access(s) = OptionBoolValue(text); };
  return d;
}

template <typename Settings, typename Access>
OptionDeclaration<Settings> NumberOption(std::string name, Access access, OptionRange range,
                                         std::string help = "") {
  using Value = std::decay_t<decltype(access(std::declval<Settings&>()))>;
  OptionDeclaration<Settings> d;
  d.name = std::move(name);
  d.type = std::is_integral_v<Value> ? OptionType::kInteger : OptionType::kNumber;
  d.range = range;
  if constexpr (std::is_integral_v<Value>) {
    // What the field can hold bounds what is accepted: 4294967296 never wraps to 0.
    d.check = [](const std::string& text) -> std::string {
      const double value = std::stod(text);
      if (value >= static_cast<double>(std::numeric_limits<Value>::lowest()) &&
          value <= static_cast<double>(std::numeric_limits<Value>::max())) {
        return "";
      }
      return "must be at most " + std::to_string(std::numeric_limits<Value>::max()) + ", got " +
             text;
    };
  }
  d.help = std::move(help);
  d.text = [access](const Settings& s) -> std::string {
    if constexpr (std::is_integral_v<Value>) return std::to_string(access(s));
    return FormatOptionNumber(static_cast<double>(access(s)));
  };
  d.store = [access](Settings& s, const std::string& text) {
    if constexpr (std::is_integral_v<Value>) {
      access(s) = static_cast<Value>(std::stoll(text));
    } else {
      access(s) = static_cast<Value>(std::stod(text));
    }
  };
  return d;
}

// A free text option (a path, "lat,lon,alt"): whatever it holds is checked where it is used.
template <typename Settings, typename Access>
OptionDeclaration<Settings> TextOption(std::string name, Access access, std::string help) {
  OptionDeclaration<Settings> d;
  d.name = std::move(name);
  d.type = OptionType::kText;
  d.help = std::move(help);
  d.text = [access](const Settings& s) -> std::string { return access(s); };
  d.store = [access](Settings& s, const std::string& text) { access(s) = text; };
  return d;
}

// An option taking one of the words of `names`, each naming a value of the field's type.
template <typename Settings, typename Value, typename Access>
OptionDeclaration<Settings> ChoiceOption(std::string name, Access access,
                                         std::vector<std::pair<std::string, Value>> names,
                                         std::string help) {
  OptionDeclaration<Settings> d;
  d.name = std::move(name);
  d.type = OptionType::kChoice;
  d.help = std::move(help);
  for (const auto& entry : names) d.choices.push_back(entry.first);
  d.text = [access, names](const Settings& s) -> std::string {
    for (const auto& entry : names) {
      if (entry.second == access(s)) return entry.first;
    }
    return "?";
  };
  d.store = [access, names](Settings& s, const std::string& text) {
    for (const auto& entry : names) {
      if (entry.first == text) access(s) = entry.second;
    }
  };
  return d;
}

template <typename Settings>
using OptionTable = std::vector<OptionDeclaration<Settings>>;

// Appends `inner`'s declarations to `out`, bound to the part of an Outer that `access` returns
// (a generic lambda: [](auto& o) -> auto& { return o.mapper; }): one declaration serves every
// settings struct that holds its struct.
template <typename Outer, typename Inner, typename Access>
void AppendOptions(const OptionTable<Inner>& inner, Access access, OptionTable<Outer>* out) {
  for (const OptionDeclaration<Inner>& d : inner) {
    OptionDeclaration<Outer> lifted;
    lifted.name = d.name;
    lifted.former_names = d.former_names;
    lifted.colmap_names = d.colmap_names;
    lifted.type = d.type;
    lifted.range = d.range;
    lifted.choices = d.choices;
    lifted.help = d.help;
    lifted.required = d.required;
    lifted.ignored_because = d.ignored_because;
    lifted.check = d.check;
    lifted.text = [text = d.text, access](const Outer& s) { return text(access(s)); };
    lifted.store = [store = d.store, access](Outer& s, const std::string& value) {
      store(access(s), value);
    };
    out->push_back(std::move(lifted));
  }
}

// The declaration named `name` (or formerly named so), or nullptr.
template <typename Settings>
const OptionDeclaration<Settings>* FindOption(const OptionTable<Settings>& table,
                                              const std::string& name) {
  for (const OptionDeclaration<Settings>& d : table) {
    const std::vector<std::string> names = d.AllNames();
    if (std::find(names.begin(), names.end(), name) != names.end()) return &d;
  }
  return nullptr;
}

// `declaration` with `former` as an alias of its name.
template <typename Settings>
OptionDeclaration<Settings> FormerlyNamed(OptionDeclaration<Settings> declaration,
                                          std::string former) {
  declaration.former_names.push_back(std::move(former));
  return declaration;
}

// `declaration` with `check` (the problem with a value, or "") run after its own checks: a rule
// a range cannot state ("0 or >= 2").
template <typename Settings>
OptionDeclaration<Settings> AlsoChecked(OptionDeclaration<Settings> declaration,
                                        std::function<std::string(const std::string&)> check) {
  declaration.check = [first = declaration.check, check](const std::string& text) {
    const std::string problem = first ? first(text) : "";
    return problem.empty() ? check(text) : problem;
  };
  return declaration;
}

// `declaration` with COLMAP's `names` for it as aliases.
template <typename Settings>
OptionDeclaration<Settings> ColmapNamed(OptionDeclaration<Settings> declaration,
                                        std::vector<std::string> names) {
  for (std::string& name : names) declaration.colmap_names.push_back(std::move(name));
  return declaration;
}

// `declaration`, which a command cannot run without.
template <typename Settings>
OptionDeclaration<Settings> Required(OptionDeclaration<Settings> declaration) {
  declaration.required = true;
  return declaration;
}

// A COLMAP option ramap accepts and drops, with the reason the note gives.
template <typename Settings>
OptionDeclaration<Settings> IgnoredColmapOption(std::string name, std::string because) {
  OptionDeclaration<Settings> d;
  d.name = std::move(name);
  d.type = OptionType::kText;
  d.help = "COLMAP's option, accepted and ignored: " + because;
  d.ignored_because = std::move(because);
  d.text = [](const Settings&) { return std::string(); };
  d.store = [](Settings&, const std::string&) {};
  return d;
}

// The names of the options that do something (COLMAP's ignored ones left out).
template <typename Settings>
std::vector<std::string> OptionNames(const OptionTable<Settings>& table) {
  std::vector<std::string> names;
  for (const OptionDeclaration<Settings>& d : table) {
    if (d.ignored_because.empty()) names.push_back(d.name);
  }
  return names;
}

// What is wrong with `text` as this option's value ("" when nothing is).
template <typename Settings>
std::string OptionProblem(const OptionDeclaration<Settings>& d, const std::string& text) {
  std::string problem = OptionValueProblem(d.type, d.range, d.choices, text);
  if (problem.empty() && d.check) problem = d.check(text);
  return problem;
}

// Checks `text` against the declaration and stores it; throws InputError("--name", problem).
template <typename Settings>
void SetOption(const OptionDeclaration<Settings>& d, const std::string& text, Settings* settings) {
  const std::string problem = OptionProblem(d, text);
  if (!problem.empty()) throw InputError("--" + d.name, problem);
  d.store(*settings, text);
}

// SetOption by name; an unknown name throws InputError with UnknownOptionMessage's text.
template <typename Settings>
void SetOption(const OptionTable<Settings>& table, const std::string& name, const std::string& text,
               Settings* settings) {
  const OptionDeclaration<Settings>* d = FindOption(table, name);
  if (d == nullptr) {
    throw InputError("--" + name, UnknownOptionMessage(name, OptionNames(table)));
  }
  SetOption(*d, text, settings);
}

// Throws InputError naming the first option whose value in `settings` its declaration refuses
// (for settings filled in by code rather than parsed).
template <typename Settings>
void CheckOptionValues(const OptionTable<Settings>& table, const Settings& settings) {
  for (const OptionDeclaration<Settings>& d : table) {
    const std::string problem = OptionProblem(d, d.text(settings));
    if (!problem.empty()) throw InputError("--" + d.name, problem);
  }
}

// What a reader of the help or the options reference is told the values may be:
// "integer >= 1", "number > 0 and < 90", "0|1", "grid|random|roi|ransac5".
std::string OptionValueHint(OptionType type, const OptionRange& range,
                            const std::vector<std::string>& choices);

// The value's type as a command line's help shows it: "INT", "FLOAT", "0|1", "grid|random".
std::string OptionTypeName(OptionType type, const std::vector<std::string>& choices);

// The options as a Markdown table: | option | default | values | what it does |; COLMAP's options
// that are accepted and ignored are listed after it.
template <typename Settings>
std::string OptionTableMarkdown(const OptionTable<Settings>& table, const Settings& defaults) {
  std::string out = "| option | default | values | what it does |\n|---|---|---|---|\n";
  std::string ignored;
  for (const OptionDeclaration<Settings>& d : table) {
    if (!d.ignored_because.empty()) {
      ignored += "- `--" + d.name + "`: " + d.ignored_because + "\n";
      continue;
    }
    std::string help;
    for (const char c : d.help) help += c == '|' ? std::string("\\|") : std::string(1, c);
    for (const std::string& former : d.former_names) help += " (formerly `--" + former + "`)";
    for (const std::string& colmap : d.colmap_names) help += " (COLMAP: `--" + colmap + "`)";
    out += "| `--" + d.name + "` | " + d.text(defaults) + " | " +
           OptionValueHint(d.type, d.range, d.choices) + " | " + help + " |\n";
  }
  if (!ignored.empty()) out += "\nCOLMAP's options accepted and ignored:\n\n" + ignored;
  return out;
}

}  // namespace ramap
