// ParseNumberList: "a,b,c" lists as options take them, and the option named for an item that is
// not a number.
#include "ramap/util/number_list.h"

#include <gtest/gtest.h>

#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {

TEST(NumberList, CommaSeparatedNumbersInTheirOrder) {
  EXPECT_EQ(ParseNumberList("2759.48,2764.16,1520.69,1006.81", "--ImageReader.camera_params"),
            (std::vector<double>{2759.48, 2764.16, 1520.69, 1006.81}));
  EXPECT_EQ(ParseNumberList("-1e-3,0,7", "--x"), (std::vector<double>{-1e-3, 0.0, 7.0}));
  EXPECT_EQ(ParseNumberList("42", "--x"), (std::vector<double>{42.0}));
}

TEST(NumberList, SpacesAroundAnItemAreAllowed) {
  EXPECT_EQ(ParseNumberList(" 1, 2 ,3 ", "--x"), (std::vector<double>{1.0, 2.0, 3.0}));
}

TEST(NumberList, EmptyTextGivesNoNumbers) { EXPECT_TRUE(ParseNumberList("", "--x").empty()); }

TEST(NumberList, AnItemThatIsNotANumberNamesTheOptionAndTheItem) {
  test::ExpectInputError([] { ParseNumberList("500,abc,320", "--ImageReader.camera_params"); },
                         {"--ImageReader.camera_params", "'abc' is not a number"});
  // A number followed by anything but spaces is not a number either.
  test::ExpectInputError([] { ParseNumberList("500,320px", "--x"); }, {"--x", "'320px'"});
  // An empty item between two commas.
  test::ExpectInputError([] { ParseNumberList("1,,2", "--x"); }, {"--x", "''"});
}

}  // namespace
}  // namespace ramap
