// The --PosePrior.* source options: each bound to its PosePriorSource field, with the documented
// defaults and the prior types accepted.
#include "ramap/mapper/pose_prior_source.h"

#include <gtest/gtest.h>

namespace ramap {
namespace {

std::string Text(const std::string& name, const PosePriorSource& source) {
  const OptionDeclaration<PosePriorSource>* d = FindOption(PosePriorSourceOptionTable(), name);
  EXPECT_NE(d, nullptr) << "--" << name;
  return d == nullptr ? "" : d->text(source);
}

TEST(PosePriorSource, DefaultsAsDocumented) {
  const PosePriorSource defaults;
  EXPECT_EQ(Text("PosePrior.path", defaults), "");
  EXPECT_EQ(Text("PosePrior.type", defaults), "auto");
  EXPECT_EQ(Text("PosePrior.origin", defaults), "");
  EXPECT_EQ(Text("PosePrior.from_database", defaults), "1");
  // Consumer GPS: a few metres horizontally, about half as good vertically.
  EXPECT_EQ(Text("PosePrior.std_x_m", defaults), "3");
  EXPECT_EQ(Text("PosePrior.std_y_m", defaults), "3");
  EXPECT_EQ(Text("PosePrior.std_z_m", defaults), "6");
  EXPECT_EQ(Text("PosePrior.max_distance_from_origin_m", defaults), "100000");
  EXPECT_NO_THROW(CheckOptionValues(PosePriorSourceOptionTable(), defaults));
}

TEST(PosePriorSource, EachOptionSetsItsField) {
  const auto& table = PosePriorSourceOptionTable();
  PosePriorSource source;
  SetOption(table, "PosePrior.path", "gps.txt", &source);
  SetOption(table, "PosePrior.type", "enu", &source);
  SetOption(table, "PosePrior.origin", "48.1,11.5,520", &source);
  SetOption(table, "PosePrior.from_database", "0", &source);
  SetOption(table, "PosePrior.std_x_m", "1.5", &source);
  SetOption(table, "PosePrior.std_y_m", "2.5", &source);
  SetOption(table, "PosePrior.std_z_m", "4.5", &source);
  SetOption(table, "PosePrior.max_distance_from_origin_m", "5000", &source);
  EXPECT_EQ(source.path, "gps.txt");
  EXPECT_EQ(source.type, "enu");
  EXPECT_EQ(source.origin, "48.1,11.5,520");
  EXPECT_FALSE(source.from_database);
  EXPECT_EQ(source.std_x_m, 1.5);
  EXPECT_EQ(source.std_y_m, 2.5);
  EXPECT_EQ(source.std_z_m, 4.5);
  EXPECT_EQ(source.max_distance_from_origin_m, 5000.0);
  EXPECT_EQ(table.size(), 8u);  // every field above, and no other option
}

TEST(PosePriorSource, TypesAndRangesAreChecked) {
  const auto& table = PosePriorSourceOptionTable();
  for (const std::string type : {"auto", "wgs84", "enu", "ecef", "xyz"}) {
    PosePriorSource source;
    EXPECT_NO_THROW(SetOption(table, "PosePrior.type", type, &source)) << type;
    EXPECT_EQ(source.type, type);
  }
  PosePriorSource source;
  EXPECT_THROW(SetOption(table, "PosePrior.type", "utm", &source), InputError);
  EXPECT_EQ(source.type, "auto");  // a refused value leaves the field as it was
  try {
    SetOption(table, "PosePrior.std_x_m", "0", &source);
    ADD_FAILURE() << "a standard deviation of 0 was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("--PosePrior.std_x_m"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace ramap
