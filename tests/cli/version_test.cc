// `ramap --version`: the version and the commit the binary was built from.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "test_support.h"

namespace ramap {
namespace {

TEST(Version, PrintsTheVersionAndTheCommitOfTheSource) {
  const test::CommandResult version = test::RunCommand(std::string(RAMAP_CLI_PATH) + " --version");
  ASSERT_EQ(version.exit_code, 0) << version.output;
  std::smatch match;
  ASSERT_TRUE(std::regex_search(
      version.output, match,
      std::regex(R"(^ramap \d+\.\d+\.\d+ \(commit ([0-9a-f]+|unknown)(-modified)?\)\n$)")))
      << version.output;
  const test::CommandResult head =
      test::RunCommand("git -C " + std::string(RAMAP_SOURCE_DIR) + " rev-parse --short=10 HEAD");
  if (head.exit_code != 0) GTEST_SKIP() << "the source is not a git checkout: " << head.output;
  EXPECT_EQ(match[1].str() + "\n", head.output.substr(head.output.find_first_not_of(" \n")));
}

}  // namespace
}  // namespace ramap
