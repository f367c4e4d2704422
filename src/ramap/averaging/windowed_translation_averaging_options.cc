#include <string>
#include <utility>
#include <vector>

#include "ramap/averaging/windowed_translation_averaging.h"

namespace ramap {

namespace {

using Table = OptionTable<WindowedTranslationOptions>;

void Declare(Table& t) {
  t.push_back(NumberOption<WindowedTranslationOptions>(
      "TranslationAveraging.window_min_num_images",
      [](auto& o) -> auto& { return o.min_num_images; }, AtLeast(0),
      "sequences of at least this many images are solved in windows joined by "
      "their shared frames and loops (0: never)"));
  t.push_back(NumberOption<WindowedTranslationOptions>(
      "TranslationAveraging.window_frames", [](auto& o) -> auto& { return o.window_frames; },
      AtLeast(3), "frames per window"));
  t.push_back(NumberOption<WindowedTranslationOptions>(
      "TranslationAveraging.window_overlap_frames",
      [](auto& o) -> auto& { return o.overlap_frames; }, AtLeast(2),
      "frames each window shares with the next (below window_frames)"));
  t.push_back(NumberOption<WindowedTranslationOptions>(
      "TranslationAveraging.window_irls_cost_tolerance",
      [](auto& o) -> auto& { return o.irls_cost_tolerance; }, OptionRange{0, false, 1, true},
      "a window's IRLS stops when a step lowers its objective by less (0: off)"));
}

}  // namespace

const OptionTable<WindowedTranslationOptions>& WindowedTranslationOptionTable() {
  static const Table table = [] {
    Table t;
    Declare(t);
    AppendOptions(
        WindowAlignmentOptionTable(), [](auto& o) -> auto& { return o.alignment; }, &t);
    return t;
  }();
  return table;
}

}  // namespace ramap
