// Rotation averaging benchmark: (a) the SE-Sync g2o files (rotations only), robust averaging
// versus the plain chordal solve; (b) a synthetic SfM-like graph of 10,000 cameras and ~200,000
// edges. Usage: ramap_bench_rotation [sesync_dir] (default ../shared/data/sesync_posegraphs
// relative to the working folder, or $RAMAP_DATA_DIR/sesync_posegraphs).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "ramap/averaging/rotation_averaging.h"
#include "ramap/graph/fiedler.h"
#include "ramap/io/g2o_reader.h"
#include "ramap/synthetic/synthetic_rotation_graph.h"
#include "ramap/util/timer.h"

namespace {

using namespace ramap;

void BenchSeSync(const std::string& dir) {
  std::printf(
      "(a) SE-Sync g2o files, rotations only; chordal cost = sum ||R_j - R_ij R_i||_F^2, "
      "unweighted, over all edges\n");
  std::printf("%-16s %6s %6s | %8s %12s %6s %6s %9s %9s %9s | %8s %12s\n", "graph", "nodes",
              "edges", "ours s", "ours cost", "pruned", "cert", "bound deg", "maxres", "lambda2",
              "chord s", "chordal cost");
  for (const char* name : {"sphere2500", "torus3D", "cubicle", "parking-garage"}) {
    const std::string path = dir + "/" + name + ".g2o";
    if (!std::filesystem::exists(path)) {
      std::printf("%-16s missing (%s)\n", name, path.c_str());
      continue;
    }
    const G2oPoseGraph g2o = ReadG2oPoseGraph(path);
    RotationAveragingOptions options;
    const RotationAveragingResult ours = AverageRotations(g2o.graph, options);
    const ChordalAveragingResult chordal = AverageRotationsChordal(g2o.graph);
    std::printf("%-16s %6zu %6zu | %8.3f %12.4f %6zu %6s %9.3f %9.3f %9.3g | %8.3f %12.4f\n", name,
                g2o.graph.node_ids.size(), g2o.graph.edges.size(), ours.timings.total,
                ChordalCost(g2o.graph, ours.rotations, {}, ours.estimated),
                ours.pruned_edges.size(), ours.certificate.certified ? "yes" : "no",
                ours.certificate.bound_deg, ours.certificate.max_residual_deg,
                ours.certificate.fiedler_value, chordal.seconds,
                ChordalCost(g2o.graph, chordal.rotations, {}, chordal.estimated));
    if (ours.certificate.refinement_skipped) {
      std::printf(
          "%-16s   certificate refinement skipped: a triangle forces a residual >= %.3f deg "
          "(maxres is the robust solution's)\n",
          "", ours.certificate.cycle_residual_lower_bound_deg);
    } else {
      std::printf("%-16s   certificate chordal cost on kept edges %.4f (iterations %d)\n", "",
                  ChordalCost(g2o.graph, ours.certificate.rotations, {}, ours.estimated),
                  ours.certificate.iterations);
    }
  }
}

void BenchSynthetic(bool windows) {
  SyntheticRotationGraphOptions options;
  options.num_nodes = 10000;
  options.forward_neighbours = 20;  // ~40 nearest neighbours per camera
  options.num_loop_edges = 200;
  options.loop_min_gap = 100;
  options.noise_deg = 2.0;
  options.outlier_fraction = 0.05;
  options.seed = 42;
  Timer timer;
  const SyntheticRotationGraph synthetic = MakeSyntheticRotationGraph(options);
  const double make_seconds = timer.ElapsedSeconds();
  size_t outliers = 0;
  for (bool o : synthetic.is_outlier) outliers += o;
  RotationAveragingOptions averaging;
  RotationAveragingResult result;
  if (windows) {
    KeyframeOptions keyframe_options;
    const Keyframes keyframes = SelectKeyframes(synthetic.graph.node_ids, keyframe_options);
    result = AverageRotationsInWindows(synthetic.graph, keyframes, averaging);
  } else {
    result = AverageRotations(synthetic.graph, averaging);
  }
  const std::vector<double> errors =
      AlignedRotationErrorsDeg(result.rotations, synthetic.true_rotations, result.estimated);
  size_t outliers_kept = 0;
  for (size_t e = 0; e < synthetic.graph.edges.size(); ++e) {
    outliers_kept += synthetic.is_outlier[e] && result.edge_status[e] == EdgeStatus::kKept;
  }
  const auto& t = result.timings;
  std::printf("(b) synthetic %s: %zu cameras, %zu edges (%zu outliers), generated in %.2f s\n",
              windows ? "windows(30)+global" : "global", synthetic.graph.node_ids.size(),
              synthetic.graph.edges.size(), outliers, make_seconds);
  std::printf(
      "    total %.3f s | windows %.3f init %.3f L1 %.3f (%d it) IRLS %.3f pruning %.3f "
      "(%d rounds, %d IRLS it in all) certificate %.3f\n",
      t.total, t.windows, t.init, t.l1, result.l1_iterations, t.irls, t.pruning,
      result.pruning_rounds, result.irls_iterations, t.certificate);
  std::printf(
      "    median rotation error %.4f deg, mean %.4f deg; pruned %zu edges, outliers kept "
      "%zu; certified %s (bound %.4f deg, max residual %.3f deg)\n",
      Median(errors),
      [&] {
        double s = 0;
        for (double e : errors) s += e;
        return s / errors.size();
      }(),
      result.pruned_edges.size(), outliers_kept, result.certificate.certified ? "yes" : "no",
      result.certificate.bound_deg, result.certificate.max_residual_deg);
  Timer chordal_timer;
  RotationGraph inliers = synthetic.graph;
  inliers.edges.clear();
  for (size_t e = 0; e < synthetic.graph.edges.size(); ++e) {
    if (!synthetic.is_outlier[e]) inliers.edges.push_back(synthetic.graph.edges[e]);
  }
  const ChordalAveragingResult reference = AverageRotationsChordal(inliers);
  std::printf("    reference: chordal on the inlier-only graph %.3f s, median error %.4f deg\n",
              reference.seconds,
              Median(AlignedRotationErrorsDeg(reference.rotations, synthetic.true_rotations,
                                              reference.estimated)));
}

}  // namespace

int main(int argc, char** argv) {
  std::string dir;
  if (argc > 1) {
    dir = argv[1];
  } else if (const char* env = std::getenv("RAMAP_DATA_DIR")) {
    dir = std::string(env) + "/sesync_posegraphs";
  } else {
    dir = "../shared/data/sesync_posegraphs";
  }
  BenchSeSync(dir);
  BenchSynthetic(/*windows=*/false);
  BenchSynthetic(/*windows=*/true);
  return 0;
}
