// What `ramap compare` compares on one database: COLMAP's incremental BA mapper (the reference of
// the speed ratios), optionally a newer COLMAP's incremental mapper and its global mapper (GLOMAP)
// as peers, and ramap's averaging mapper with and without bundle adjustment.
#pragma once

#include <string>

#include "ramap/util/option_table.h"

namespace ramap {

struct CompareOptions {
  std::string database_path;  // COLMAP database with verified matches (never changed)
  std::string output_path;    // models, logs, report.{md,json} and figures
  // The images: COLMAP's mappers read the colours from them. Empty: an empty folder in
  // output_path (the models get no colours).
  std::string image_path;
  // Ground truth and its format (tum, kitti, strecha, middlebury, colmap): both or neither.
  // Without it the other models are scored against the reference COLMAP's.
  std::string ground_truth_path;
  std::string ground_truth_format;
  // The reference mapper's binary (Debian's COLMAP 3.8).
  std::string colmap_binary = "colmap";
  // A COLMAP 4 binary (scripts/peers.sh builds one): adds its `mapper` and its `global_mapper`
  // (GLOMAP) as two more rows, each on its own copy of the database, since COLMAP 4 upgrades a
  // COLMAP 3.8 database in place. Empty: no peer rows.
  std::string peer_colmap_binary;
  // The ramap executable whose mapper is compared; empty: the running one.
  std::string ramap_binary;
  // false: intrinsics fixed in every mapper (fair with a known calibration); true: each mapper
  // refines them as its defaults do.
  bool refine_intrinsics = false;
  int num_threads = 2;  // of every mapper (the project's machine has 2 cores)
  // Also draw the figures as PNG files (trajectories, error distributions, stage times), for
  // pages that want a static picture (BENCHMARKS.md); report.html has them all, interactive.
  bool png_figures = false;
};

// `ramap compare`'s options, each declared once with its range and help (util/option_table.h);
// the binaries are checked to exist before anything runs.
const OptionTable<CompareOptions>& CompareOptionTable();

}  // namespace ramap
