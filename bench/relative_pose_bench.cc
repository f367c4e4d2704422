// Relative pose benchmark, the paper's sampler ablation on real data: for every verified pair of a
// COLMAP database, the relative rotation of each sampler (grid, random, roi) and of the RANSAC
// five-point baseline is compared with the ground truth; prints median and 90th-percentile
// rotation and translation-direction errors, rejected pairs and time per pair (one thread).
//
// Usage: ramap_bench_relative_pose NAME DATABASE GROUND_TRUTH FORMAT [NAME DATABASE ...]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "ramap/geometry/rotation.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/trajectory.h"
#include "ramap/estimators/relative_poses.h"
#include "ramap/util/timer.h"

namespace {

using namespace ramap;

double Percentile(std::vector<double> values, double q) {
  if (values.empty()) return NAN;
  std::sort(values.begin(), values.end());
  return values[std::min(values.size() - 1, static_cast<size_t>(q * values.size()))];
}

void BenchDataset(const std::string& name, const std::string& database_path,
                  const std::string& ground_truth_path, const std::string& format) {
  const FeatureDatabase database = ReadColmapDatabase(database_path);
  const ImageBearings bearings = ComputeBearings(database, database_path);
  std::vector<std::string> names;
  for (const auto& [id, image] : database.images) names.push_back(image.name);
  const std::map<std::string, Rigid3d> truth = GroundTruthByImageName(
      ReadGroundTruth(ground_truth_path, GroundTruthFormatFromName(format)), names);

  // A database from ramap's matcher also gets the grid ranked by the descriptor ratio it stores
  // instead of the Sampson error, to measure what the ratio is worth.
  const bool has_ratios =
      std::any_of(database.two_view_geometries.begin(), database.two_view_geometries.end(),
                  [](const auto& entry) { return !entry.second.inlier_ratios.empty(); });
  // The grid also with Nister's five-point essential matrices for the five-subset candidates
  // instead of Kneip's rotation-only solver (the default), to measure what the faster solver
  // costs in accuracy; and with every five-point candidate solved (no confident early stop), to
  // measure what the stop costs.
  struct Variant {
    CorrespondenceSampler sampler;
    bool use_ratios;
    bool nister_five_point;
    bool every_candidate;
  };
  std::vector<Variant> variants = {{CorrespondenceSampler::kGrid, false, false, false},
                                   {CorrespondenceSampler::kGrid, false, false, true},
                                   {CorrespondenceSampler::kGrid, false, true, false}};
  if (has_ratios) variants.push_back({CorrespondenceSampler::kGrid, true, false, false});
  for (const CorrespondenceSampler sampler :
       {CorrespondenceSampler::kRandom, CorrespondenceSampler::kRoi,
        CorrespondenceSampler::kRansac5}) {
    variants.push_back({sampler, false, false, false});
  }
  for (const Variant& variant : variants) {
    const CorrespondenceSampler sampler = variant.sampler;
    RelativePoseOptions options;
    options.sampler = sampler;
    options.use_descriptor_ratios = variant.use_ratios;
    options.nister_five_point = variant.nister_five_point;
    if (variant.every_candidate) options.confident_inlier_ratio = 2;
    const std::string label = CorrespondenceSamplerName(sampler) +
                              (has_ratios && sampler == CorrespondenceSampler::kGrid
                                   ? (variant.use_ratios ? " (ratio)" : " (Sampson)")
                                   : "") +
                              (variant.nister_five_point ? " (Nister 5-point)" : "") +
                              (variant.every_candidate ? " (every candidate)" : "");
    Timer timer;
    const std::vector<ImagePair> edges =
        EstimateRelativePoses(database, bearings, options, /*num_threads=*/1);
    const double seconds = timer.ElapsedSeconds();
    std::vector<double> rotation_errors, translation_errors;
    int rejected = 0;
    for (const ImagePair& edge : edges) {
      if (!edge.estimate.success) {
        ++rejected;
        continue;
      }
      const auto t1 = truth.find(database.images.at(edge.image_id1).name);
      const auto t2 = truth.find(database.images.at(edge.image_id2).name);
      if (t1 == truth.end() || t2 == truth.end()) continue;
      const Rigid3d cam2_from_cam1 = t2->second * t1->second.Inverse();
      rotation_errors.push_back(RotationAngleDeg(edge.estimate.rotation, cam2_from_cam1.rotation));
      if (edge.estimate.translation.norm() > 0 && cam2_from_cam1.translation.norm() > 0) {
        const double c =
            edge.estimate.translation.normalized().dot(cam2_from_cam1.translation.normalized());
        translation_errors.push_back(std::acos(std::clamp(c, -1.0, 1.0)) * kRadToDeg);
      }
    }
    std::printf("| %s | %s | %zu | %d | %.3f | %.3f | %.2f | %.2f | %.2f |\n", name.c_str(),
                label.c_str(), edges.size(), rejected, Percentile(rotation_errors, 0.5),
                Percentile(rotation_errors, 0.9), Percentile(translation_errors, 0.5),
                Percentile(translation_errors, 0.9),
                edges.empty() ? 0.0 : 1000.0 * seconds / edges.size());
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5 || (argc - 1) % 4 != 0) {
    std::fprintf(
        stderr,
        "usage: %s NAME DATABASE GROUND_TRUTH FORMAT [NAME DATABASE GROUND_TRUTH FORMAT ...]\n",
        argv[0]);
    return 1;
  }
  std::printf(
      "| data set | sampler | pairs | rejected | rot. err. median (deg) | rot. err. p90 (deg) | "
      "t dir. err. median (deg) | t dir. err. p90 (deg) | ms per pair |\n"
      "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (int k = 1; k + 3 < argc; k += 4)
    BenchDataset(argv[k], argv[k + 1], argv[k + 2], argv[k + 3]);
  return 0;
}
