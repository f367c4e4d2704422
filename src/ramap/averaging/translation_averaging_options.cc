#include <string>
#include <utility>
#include <vector>

#include "ramap/averaging/translation_averaging.h"

namespace ramap {

namespace {

using Table = OptionTable<TranslationAveragingOptions>;

void DeclarePart1(Table& t) {
  t.push_back(NumberOption<TranslationAveragingOptions>(
      "TranslationAveraging.min_triangulation_angle_deg",
      [](auto& o) -> auto& { return o.min_triangulation_angle_deg; }, Above(0, 90),
      "track rows need rays at least this far apart"));
  t.push_back(NumberOption<TranslationAveragingOptions>(
      "TranslationAveraging.max_rejection_rounds",
      [](auto& o) -> auto& { return o.max_rejection_rounds; }, AtLeast(0),
      "solve again without the rows the solution marks as outliers, this many "
      "times (0: never)"));
  t.push_back(NumberOption<TranslationAveragingOptions>(
      "TranslationAveraging.rejection_multiplier",
      [](auto& o) -> auto& { return o.rejection_multiplier; }, Above(1),
      "outliers: residuals above this many times the system's median residual"));
  t.push_back(NumberOption<TranslationAveragingOptions>(
      "TranslationAveraging.rejection_min_angle_deg",
      [](auto& o) -> auto& { return o.rejection_min_angle_deg; }, AtLeast(0),
      "a pair row is an outlier only when its direction is missed by more than this"));
  t.push_back(NumberOption<TranslationAveragingOptions>(
      "TranslationAveraging.max_num_tracks", [](auto& o) -> auto& { return o.max_num_tracks; },
      AtLeast(1), "tracks in the system at most"));
  t.push_back(NumberOption<TranslationAveragingOptions>(
      "TranslationAveraging.min_tracks_per_image",
      [](auto& o) -> auto& { return o.min_tracks_per_image; }, AtLeast(0),
      "past max_num_tracks, tracks are still used while a camera has fewer (0: "
      "off)"));
  t.push_back(ChoiceOption<TranslationAveragingOptions>(
      "TranslationAveraging.solver", [](auto& o) -> auto& { return o.solver; },
      std::vector<std::pair<std::string, TranslationSolver>>{{"irls", TranslationSolver::kIrls},
                                                             {"admm", TranslationSolver::kAdmm}},
      "the L1 solver"));
  t.push_back(NumberOption<TranslationAveragingOptions>(
      "TranslationAveraging.max_irls_iterations",
      [](auto& o) -> auto& { return o.max_irls_iterations; }, AtLeast(0),
      "iterations of the IRLS solver"));
  t.push_back(NumberOption<TranslationAveragingOptions>(
      "TranslationAveraging.irls_cost_tolerance",
      [](auto& o) -> auto& { return o.irls_cost_tolerance; }, OptionRange{0, false, 1, true},
      "stop IRLS when a step lowers its objective by less (0: off)"));
  t.push_back(NumberOption<TranslationAveragingOptions>(
      "TranslationAveraging.irls_extrapolation",
      [](auto& o) -> auto& { return o.irls_extrapolation; }, AtLeast(1, 3),
      "IRLS steps taken this many times over when that lowers the objective more "
      "(1: plain)"));
  t.push_back(NumberOption<TranslationAveragingOptions>(
      "TranslationAveraging.max_pcg_iterations",
      [](auto& o) -> auto& { return o.max_pcg_iterations; }, AtLeast(0),
      "IRLS steps reuse the last factorisation for up to this many "
      "conjugate-gradient iterations before refactorising (0: refactorise every "
      "step)"));
  t.push_back(NumberOption<TranslationAveragingOptions>(
      "TranslationAveraging.max_admm_iterations",
      [](auto& o) -> auto& { return o.max_admm_iterations; }, AtLeast(0),
      "iterations of the ADMM solver"));
}

void DeclarePart2(Table& t) {
  t.push_back(NumberOption<TranslationAveragingOptions>(
      "TranslationAveraging.admm_rho", [](auto& o) -> auto& { return o.admm_rho; }, Above(0),
      "the ADMM solver's penalty"));
  t.push_back(BoolOption<TranslationAveragingOptions>(
      "TranslationAveraging.admm_adaptive_rho",
      [](auto& o) -> auto& { return o.admm_adaptive_rho; },
      "1: the penalty follows the residuals' balance"));
  t.push_back(NumberOption<TranslationAveragingOptions>(
      "TranslationAveraging.pair_constraint_weight",
      [](auto& o) -> auto& { return o.pair_constraint_weight; }, Above(0),
      "a pair direction's weight against a track's"));
}

}  // namespace

const OptionTable<TranslationAveragingOptions>& TranslationAveragingOptionTable() {
  static const Table table = [] {
    Table t;
    DeclarePart1(t);
    DeclarePart2(t);
    return t;
  }();
  return table;
}

}  // namespace ramap
