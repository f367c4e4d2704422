#include "ramap/averaging/windowed_translation_averaging.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>

#include "ramap/util/blas_threads.h"
#include "ramap/util/error.h"
#include "ramap/util/option_check.h"
#include "ramap/util/parallel.h"
#include "ramap/util/timer.h"

namespace ramap {
namespace {

// A window's frames: [begin, end) in the ordered images.
using FrameRange = std::pair<size_t, size_t>;

// One window every window_frames, each overlap_frames longer; a rest shorter than half a window
// joins the last one.
std::vector<FrameRange> WindowRanges(size_t num_images,
                                     const WindowedTranslationOptions& windowed) {
  const size_t step = windowed.window_frames;
  const size_t length = step + windowed.overlap_frames;
  std::vector<FrameRange> ranges;
  for (size_t begin = 0;; begin += step) {
    const size_t end = begin + length;
    if (end + step / 2 >= num_images) {
      ranges.emplace_back(begin, num_images);
      return ranges;
    }
    ranges.emplace_back(begin, end);
  }
}

// What each window's solve reads: its images' rotations, the directions and tracks it touches.
struct WindowInputs {
  std::vector<std::map<uint32_t, Eigen::Quaterniond>> rotations;  // per window
  std::vector<std::vector<size_t>> directions;                    // per window: indices
  std::vector<std::vector<size_t>> tracks;                        // per window: indices
  std::vector<PairDirection> cross_directions;                    // of images in no common window
};

// The windows an image pair shares (each image is in one or two windows).
std::vector<int> SharedWindows(const std::vector<int>& windows1, const std::vector<int>& windows2) {
  std::vector<int> shared;
  for (const int w : windows1) {
    if (std::find(windows2.begin(), windows2.end(), w) != windows2.end()) shared.push_back(w);
  }
  return shared;
}

WindowInputs SplitIntoWindows(const std::vector<uint32_t>& ordered,
                              const std::vector<FrameRange>& ranges,
                              const std::map<uint32_t, Eigen::Quaterniond>& rotations,
                              const std::vector<PairDirection>& pair_directions,
                              const std::vector<Track>& tracks) {
  WindowInputs inputs;
  inputs.rotations.resize(ranges.size());
  inputs.directions.resize(ranges.size());
  inputs.tracks.resize(ranges.size());
  std::unordered_map<uint32_t, std::vector<int>> windows_of_image;  // image -> its windows
  for (size_t w = 0; w < ranges.size(); ++w) {
    for (size_t k = ranges[w].first; k < ranges[w].second; ++k) {
      inputs.rotations[w].emplace(ordered[k], rotations.at(ordered[k]));
      windows_of_image[ordered[k]].push_back(static_cast<int>(w));
    }
  }
  const auto windows_of = [&](uint32_t image_id) -> const std::vector<int>* {
    const auto found = windows_of_image.find(image_id);
    return found == windows_of_image.end() ? nullptr : &found->second;
  };
  for (size_t k = 0; k < pair_directions.size(); ++k) {
    const std::vector<int>* windows1 = windows_of(pair_directions[k].image_id1);
    const std::vector<int>* windows2 = windows_of(pair_directions[k].image_id2);
    if (!windows1 || !windows2) continue;
    const std::vector<int> shared = SharedWindows(*windows1, *windows2);
    for (const int w : shared) inputs.directions[w].push_back(k);
    if (shared.empty()) inputs.cross_directions.push_back(pair_directions[k]);
  }
  std::vector<int> touched;
  for (size_t t = 0; t < tracks.size(); ++t) {
    touched.clear();
    for (const TrackElement& element : tracks[t]) {
      if (const std::vector<int>* in = windows_of(element.image_id)) {
        touched.insert(touched.end(), in->begin(), in->end());
      }
    }
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    for (const int w : touched) inputs.tracks[w].push_back(t);
  }
  return inputs;
}

// Window w's own translation averaging: its directions, its part of each track it touches, and a
// share of the track cap as large as its share of the images (the per-image quota stays).
TranslationAveragingResult SolveWindow(size_t w, const WindowInputs& inputs,
                                       const std::vector<PairDirection>& pair_directions,
                                       const std::vector<Track>& tracks,
                                       const KeypointBearings& bearings,
                                       const TranslationAveragingOptions& options,
                                       size_t num_images) {
  const std::map<uint32_t, Eigen::Quaterniond>& rotations = inputs.rotations[w];
  std::vector<PairDirection> directions;
  directions.reserve(inputs.directions[w].size());
  for (const size_t k : inputs.directions[w]) directions.push_back(pair_directions[k]);
  std::vector<Track> parts;
  parts.reserve(inputs.tracks[w].size());
  Track part;
  for (const size_t t : inputs.tracks[w]) {
    part.clear();
    for (const TrackElement& element : tracks[t]) {
      if (rotations.count(element.image_id)) part.push_back(element);
    }
    if (part.size() >= 2) parts.push_back(part);
  }
  TranslationAveragingOptions local = options;
  local.num_threads = 1;
  local.max_num_tracks = std::max<int>(
      1, static_cast<int>(std::lround(static_cast<double>(options.max_num_tracks) *
                                      rotations.size() / std::max<size_t>(1, num_images))));
  return AverageTranslations(rotations, directions, parts, bearings, local);
}

// Solves the windows of `ranges` that `solved` does not hold yet, on `num_threads` threads. A
// window whose solve fails gets no centres.
void SolveNewWindows(const std::vector<FrameRange>& ranges, const WindowInputs& inputs,
                     const std::vector<PairDirection>& pair_directions,
                     const std::vector<Track>& tracks, const KeypointBearings& bearings,
                     const TranslationAveragingOptions& options, int num_threads,
                     std::map<FrameRange, TranslationAveragingResult>* solved) {
  std::vector<size_t> missing;
  for (size_t w = 0; w < ranges.size(); ++w) {
    if (!solved->count(ranges[w])) missing.push_back(w);
  }
  const size_t num_images = ranges.empty() ? 0 : ranges.back().second;
  std::vector<TranslationAveragingResult> results(missing.size());
  const SingleBlasThread single_blas_thread;  // the windows are small and solved side by side
  ParallelFor(missing.size(), num_threads, [&](size_t k) {
    try {
      results[k] =
          SolveWindow(missing[k], inputs, pair_directions, tracks, bearings, options, num_images);
    } catch (const StageFailure&) {
      results[k] = TranslationAveragingResult();  // no centres: merged with its neighbours
    }
  });
  for (size_t k = 0; k < missing.size(); ++k) {
    (*solved)[ranges[missing[k]]] = std::move(results[k]);
  }
}

// Merges each pair of neighbouring windows that are not tied (WindowsTied) into one window with
// a window of context on either side, which ties the parts before and after a standstill by the
// tracks that span it. Returns whether any was merged.
bool MergeUntiedWindows(const std::map<FrameRange, TranslationAveragingResult>& solved,
                        std::vector<FrameRange>* ranges) {
  // merge_with_previous[w]: window w joins window w - 1.
  std::vector<bool> merge_with_previous(ranges->size(), false);
  for (size_t w = 1; w < ranges->size(); ++w) {
    if (WindowsTied(solved.at((*ranges)[w - 1]).centers, solved.at((*ranges)[w]).centers)) continue;
    for (size_t k = std::max<size_t>(w, 2) - 1; k <= std::min(w + 1, ranges->size() - 1); ++k) {
      merge_with_previous[k] = true;
    }
  }
  std::vector<FrameRange> merged = {ranges->front()};
  for (size_t w = 1; w < ranges->size(); ++w) {
    if (merge_with_previous[w]) {
      merged.back().second = (*ranges)[w].second;
    } else {
      merged.push_back((*ranges)[w]);
    }
  }
  const bool any = merged.size() < ranges->size();
  *ranges = std::move(merged);
  return any;
}

// Sums the windows' counts into `result`.
void AddWindowCounts(const TranslationAveragingResult& window, TranslationAveragingResult* result) {
  result->num_tracks_used += window.num_tracks_used;
  result->num_constraints += window.num_constraints;
  result->num_solver_iterations += window.num_solver_iterations;
  result->num_factorizations += window.num_factorizations;
  result->l1_cost += window.l1_cost;
  result->num_rejected_rows += window.num_rejected_rows;
  result->rejected_pair_rows.insert(result->rejected_pair_rows.end(),
                                    window.rejected_pair_rows.begin(),
                                    window.rejected_pair_rows.end());
}

// Each image's centre: the mean of its placed windows' centres.
std::map<uint32_t, Eigen::Vector3d> PlacedCenters(
    const std::vector<std::map<uint32_t, Eigen::Vector3d>>& local,
    const std::vector<WindowPlacement>& placements) {
  std::map<uint32_t, std::pair<Eigen::Vector3d, int>> sums;
  for (size_t w = 0; w < local.size(); ++w) {
    for (const auto& [image_id, center] : local[w]) {
      auto& [sum, count] = sums.try_emplace(image_id, Eigen::Vector3d::Zero(), 0).first->second;
      sum += placements[w].scale * center + placements[w].translation;
      ++count;
    }
  }
  std::map<uint32_t, Eigen::Vector3d> centers;
  for (const auto& [image_id, sum] : sums) centers[image_id] = sum.first / sum.second;
  return centers;
}

// The documented gauge of TranslationAveragingResult: the first positioned image of `ordered` at
// the origin, the mean projected pair baseline 1.
void MoveToGauge(const std::vector<uint32_t>& ordered,
                 const std::vector<PairDirection>& pair_directions,
                 TranslationAveragingResult* result) {
  std::map<uint32_t, Eigen::Vector3d>& centers = result->centers;
  if (centers.size() < 2) throw StageFailure("window alignment: fewer than two cameras placed");
  const auto first = std::find_if(ordered.begin(), ordered.end(),
                                  [&](uint32_t image_id) { return centers.count(image_id); });
  result->gauge_image_id = *first;
  const Eigen::Vector3d origin = centers.at(*first);
  double projected = 0;
  int num_pairs = 0;
  for (const PairDirection& pair : pair_directions) {
    const auto found1 = centers.find(pair.image_id1), found2 = centers.find(pair.image_id2);
    if (found1 == centers.end() || found2 == centers.end() || !(pair.direction.norm() > 0)) {
      continue;
    }
    projected += pair.direction.normalized().dot(found2->second - found1->second);
    ++num_pairs;
  }
  if (!(projected > 0)) {
    throw StageFailure("window alignment: the joined windows do not fit the pair directions");
  }
  for (auto& [image_id, center] : centers) center = (center - origin) * (num_pairs / projected);
}

}  // namespace

void WindowedTranslationOptions::Check() const {
  CheckOptionValues(WindowedTranslationOptionTable(), *this);
  CheckOption(overlap_frames < window_frames, "--TranslationAveraging.window_overlap_frames",
              "below --TranslationAveraging.window_frames", overlap_frames);
}

TranslationAveragingResult AverageTranslationsInWindows(
    const std::vector<uint32_t>& order, const std::map<uint32_t, Eigen::Quaterniond>& rotations,
    const std::vector<PairDirection>& pair_directions, const std::vector<Track>& tracks,
    const KeypointBearings& bearings, const TranslationAveragingOptions& options,
    const WindowedTranslationOptions& windowed, int num_threads) {
  options.Check();
  windowed.Check();
  Timer timer;
  std::vector<uint32_t> ordered;
  for (const uint32_t image_id : order) {
    if (rotations.count(image_id)) ordered.push_back(image_id);
  }
  // Windows that a standstill or a failed solve leaves untied to a neighbour are merged with it
  // (and a window of context on either side) and solved again, until every neighbour is tied (at
  // worst into one window: one system).
  TranslationAveragingOptions window_options = options;
  window_options.irls_cost_tolerance = windowed.irls_cost_tolerance;
  std::vector<FrameRange> ranges = WindowRanges(ordered.size(), windowed);
  std::map<FrameRange, TranslationAveragingResult> solved;
  WindowInputs inputs;
  do {
    inputs = SplitIntoWindows(ordered, ranges, rotations, pair_directions, tracks);
    SolveNewWindows(ranges, inputs, pair_directions, tracks, bearings, window_options, num_threads,
                    &solved);
  } while (MergeUntiedWindows(solved, &ranges));
  TranslationAveragingResult result;
  std::vector<std::map<uint32_t, Eigen::Vector3d>> local;
  for (const FrameRange& range : ranges) {
    AddWindowCounts(solved.at(range), &result);
    local.push_back(std::move(solved.at(range).centers));
  }
  WindowAlignmentOptions alignment = windowed.alignment;
  alignment.num_threads = num_threads;
  const std::vector<WindowPlacement> placements =
      AlignWindows(local, inputs.cross_directions, alignment);
  result.centers = PlacedCenters(local, placements);
  result.num_windows = static_cast<int>(ranges.size());
  result.num_constraints += static_cast<int>(inputs.cross_directions.size());
  for (const auto& [image_id, rotation] : rotations) {
    (void)rotation;
    if (!result.centers.count(image_id)) result.unconstrained_images.push_back(image_id);
  }
  MoveToGauge(ordered, pair_directions, &result);
  result.seconds = timer.ElapsedSeconds();
  return result;
}

}  // namespace ramap
