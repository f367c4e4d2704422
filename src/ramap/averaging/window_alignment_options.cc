#include <string>
#include <utility>
#include <vector>

#include "ramap/averaging/window_alignment.h"

namespace ramap {

namespace {

using Table = OptionTable<WindowAlignmentOptions>;

void Declare(Table& t) {
  t.push_back(NumberOption<WindowAlignmentOptions>(
      "TranslationAveraging.window_max_num_iterations",
      [](auto& o) -> auto& { return o.max_num_iterations; }, AtLeast(0),
      "Ceres iterations placing the windows by their loops (0: the chain of shared frames "
      "alone)"));
  t.push_back(NumberOption<WindowAlignmentOptions>(
      "TranslationAveraging.window_direction_sigma_rad",
      [](auto& o) -> auto& { return o.direction_sigma_rad; }, Above(0),
      "noise of a direction between windows; larger angles are weighed as their size"));
  t.push_back(NumberOption<WindowAlignmentOptions>(
      "TranslationAveraging.window_huber_overlap_residuals",
      [](auto& o) -> auto& { return o.huber_overlap_residuals; }, Above(0),
      "shared-frame residuals past this many times the chain's median are weighed as their "
      "size"));
  t.push_back(NumberOption<WindowAlignmentOptions>(
      "TranslationAveraging.window_max_directions_per_pair",
      [](auto& o) -> auto& { return o.max_directions_per_window_pair; }, AtLeast(0),
      "directions used per pair of windows at most (0: all)"));
}

}  // namespace

const OptionTable<WindowAlignmentOptions>& WindowAlignmentOptionTable() {
  static const Table table = [] {
    Table t;
    Declare(t);
    return t;
  }();
  return table;
}

}  // namespace ramap
