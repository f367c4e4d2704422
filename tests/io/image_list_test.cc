// Image lists: names trimmed, blank and '#' lines skipped, a clear error for a list that names
// nothing or cannot be read.
#include "ramap/io/image_list.h"

#include <gtest/gtest.h>

#include <fstream>

#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {

TEST(ImageList, NamesTrimmedCommentsAndBlankLinesSkipped) {
  test::TempDir dir;
  const std::string path = dir / "list.txt";
  std::ofstream(path) << "# frames of the first drive\n  a.png \r\n\n\tsub/b.jpg\n   # c.png\n";
  EXPECT_EQ(ReadImageList(path), (std::vector<std::string>{"a.png", "sub/b.jpg"}));
}

TEST(ImageList, AListNamingNothingOrMissingIsAnErrorNamingIt) {
  test::TempDir dir;
  const std::string empty = dir / "empty.txt";
  std::ofstream(empty) << "# nothing\n\n";
  test::ExpectInputError([&] { ReadImageList(empty); }, {"empty.txt"});
  EXPECT_THROW(ReadImageList(dir / "missing.txt"), InputError);
}

}  // namespace
}  // namespace ramap
