// `ramap matcher --database_path DB [--Matching.mode sequential|exhaustive]`: matches and verified
// two-view geometries of a database's images (features from ramap feature_extractor), written
// back in COLMAP's schema.
#include <iostream>

#include "options.h"
#include "ramap/jobs/reconstruct_job.h"

namespace ramap::cli {
namespace {

struct MatcherCommand {
  std::string database_path;
  FeatureOptions options;
  int log_level = 1;
};

const OptionTable<MatcherCommand>& MatcherCommandTable() {
  static const OptionTable<MatcherCommand> table = [] {
    OptionTable<MatcherCommand> t;
    t.push_back(Required(PathOption<MatcherCommand>(
        "database_path", [](auto& o) -> auto& { return o.database_path; },
        "COLMAP database with descriptors")));
    t.push_back(LogLevelOption<MatcherCommand>([](auto& o) -> auto& { return o.log_level; }));
    AppendOptions(
        MatchingOptionTable(), [](auto& o) -> auto& { return o.options; }, &t);
    return t;
  }();
  return table;
}

}  // namespace

std::string MatcherOptionsMarkdown() {
  return OptionTableMarkdown(MatcherCommandTable(), MatcherCommand());
}

int RunMatcher(int argc, char** argv) {
  CLI::App app(
      "Matches and verifies image pairs of a COLMAP database written by feature_extractor.",
      "ramap matcher");
  MatcherCommand c;
  if (const auto code = ParseCommandLine(app, MatcherCommandTable(), &c, argc, argv)) return *code;
  MatchDatabaseFile(c.database_path, c.options, ProgressStream(c.log_level));
  std::cout << "Wrote " << c.database_path << "\n";
  return 0;
}

}  // namespace ramap::cli
