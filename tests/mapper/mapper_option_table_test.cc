// The mapper's option table as the commands read it: every name accepted once, every declaration
// bound to a field of its own whose default it accepts, and the sections a command registers.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "ramap/mapper/mapper_options.h"

namespace ramap {
namespace {

// Another value `d` accepts than `current`, or "" when none is found.
std::string OtherValue(const OptionDeclaration<MapperOptions>& d, const std::string& current) {
  std::vector<std::string> candidates;
  switch (d.type) {
    case OptionType::kBool:
      candidates = {current == "1" ? "0" : "1"};
      break;
    case OptionType::kChoice:
      candidates = d.choices;
      break;
    case OptionType::kText:
      candidates = {"other.txt"};
      break;
    case OptionType::kInteger: {
      const long long value = std::stoll(current);
      candidates = {std::to_string(value + 1), std::to_string(value - 1)};
      break;
    }
    case OptionType::kNumber: {
      const double value = std::stod(current);
      for (const double other :
           {value * 1.1, value * 0.9, value * 1.5, value / 2, value + 1, value - 1, 0.5, 0.0}) {
        candidates.push_back(FormatOptionNumber(other));
      }
      break;
    }
  }
  for (const std::string& candidate : candidates) {
    if (candidate != current && OptionProblem(d, candidate).empty()) return candidate;
  }
  return "";
}

std::vector<std::string> Texts(const MapperOptions& options) {
  std::vector<std::string> texts;
  for (const auto& d : MapperOptionTable()) texts.push_back(d.text(options));
  return texts;
}

TEST(MapperOptionTable, EveryNameIsAcceptedForOneOptionOnly) {
  std::map<std::string, std::string> owner;
  for (const auto& d : MapperOptionTable()) {
    for (const std::string& name : d.AllNames()) {
      const auto [it, inserted] = owner.emplace(name, d.name);
      EXPECT_TRUE(inserted) << "--" << name << " names both --" << it->second << " and --"
                            << d.name;
    }
  }
  EXPECT_GT(owner.size(), 50u);
}

TEST(MapperOptionTable, EveryDefaultIsAValueItsDeclarationAccepts) {
  const MapperOptions defaults;
  for (const auto& d : MapperOptionTable()) {
    EXPECT_EQ(OptionProblem(d, d.text(defaults)), "") << "--" << d.name;
  }
  EXPECT_NO_THROW(CheckOptionValues(MapperOptionTable(), defaults));
}

TEST(MapperOptionTable, EachDeclarationSetsAFieldOfItsOwn) {
  const MapperOptions defaults;
  const std::vector<std::string> default_texts = Texts(defaults);
  const auto& table = MapperOptionTable();
  for (size_t k = 0; k < table.size(); ++k) {
    const auto& d = table[k];
    if (!d.ignored_because.empty()) continue;  // COLMAP's options accepted and dropped
    const std::string other = OtherValue(d, default_texts[k]);
    ASSERT_FALSE(other.empty()) << "no other value found for --" << d.name;
    MapperOptions options;
    SetOption(d, other, &options);
    const std::vector<std::string> texts = Texts(options);
    EXPECT_EQ(texts[k], other) << "--" << d.name << " does not read back what it stored";
    for (size_t j = 0; j < table.size(); ++j) {
      if (j != k && table[j].ignored_because.empty()) {
        EXPECT_EQ(texts[j], default_texts[j])
            << "setting --" << d.name << " changed --" << table[j].name;
      }
    }
  }
}

TEST(MapperOptionTable, OptionsReachTheStagesFields) {
  MapperOptions options;
  SetOption(MapperOptionTable(), "Mapper.refine", "0", &options);
  SetOption(MapperOptionTable(), "Mapper.num_threads", "3", &options);
  SetOption(MapperOptionTable(), "PosePrior.std_z_m", "9.5", &options);
  SetOption(MapperOptionTable(), "TranslationAveraging.window_frames", "40", &options);
  SetOption(MapperOptionTable(), "PairDirection.min_num_matches", "20", &options);
  // A former name still reaches the option.
  SetOption(MapperOptionTable(), "PoseGraph.sequential", "1", &options);
  EXPECT_FALSE(options.refine);
  EXPECT_EQ(options.num_threads, 3);
  EXPECT_EQ(options.prior_source.std_z_m, 9.5);
  EXPECT_EQ(options.translation_windows.window_frames, 40);
  EXPECT_EQ(options.pair_direction.min_num_matches, 20);
  EXPECT_EQ(options.order, InputOrder::kSequential);
}

TEST(MapperOptionTable, SectionsAreTheTablesDeclarationsInItsOrder) {
  const OptionTable<MapperOptions> subset =
      MapperOptionSections({"RelativePose", "PosePrior"}, {"Mapper.num_threads"});
  std::vector<std::string> expected;
  for (const auto& d : MapperOptionTable()) {
    if (d.Section() == "RelativePose" || d.Section() == "PosePrior" ||
        d.name == "Mapper.num_threads") {
      expected.push_back(d.name);
    }
  }
  std::vector<std::string> names;
  for (const auto& d : subset) names.push_back(d.name);
  EXPECT_EQ(names, expected);
  EXPECT_GT(names.size(), 8u);
  // The subset's declarations still set the mapper's fields.
  MapperOptions options;
  SetOption(subset, "Mapper.num_threads", "4", &options);
  EXPECT_EQ(options.num_threads, 4);
  EXPECT_TRUE(MapperOptionSections({"NoSuchSection"}).empty());
}

}  // namespace
}  // namespace ramap
