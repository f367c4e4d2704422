// The mapper runs of a comparison as command lines, with each mapper's options of the same meaning
// (threads, fixed or refined intrinsics).
#pragma once

#include <string>
#include <vector>

#include "ramap/compare/compare_options.h"
#include "ramap/compare/comparison.h"

namespace ramap {

struct MapperPlan {
  std::string name;     // the row's name
  std::string folder;   // under the output path; replaced whole by each run
  std::string command;  // the whole command line, paths quoted for the shell
  // The database this run reads: the given one, or (peers) a copy made before the clock starts,
  // removed after the run.
  std::string database_path;
  bool on_database_copy = false;
  // The copy is rewritten as a COLMAP 3.8 database: COLMAP 3.8 reads no later generation (and
  // would stamp its own version on one).
  bool copy_as_colmap38 = false;
};

// The runs in report order: COLMAP; with a peer binary, "COLMAP <peer_version>" (its incremental
// mapper) and GLOMAP; ramap (--Mapper.refine 0: averaging, then BA on a subset of the tracks);
// ramap+BA.
std::vector<MapperPlan> MapperPlans(const CompareOptions& options, const std::string& peer_version);

// The version a COLMAP binary prints in its help ("4.1.1"), or "peer" when it names none.
std::string ColmapVersion(const std::string& colmap_binary);

// `text` quoted for the shell.
std::string ShellQuote(const std::string& text);

}  // namespace ramap
