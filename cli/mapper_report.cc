#include "mapper_report.h"

#include <cmath>
#include <iomanip>

#include "ramap/mapper/stage_log.h"

namespace ramap::cli {

void PrintPriorAlignment(const MapperSummary& summary, std::ostream& out) {
  for (size_t k = 0; k < summary.components.size(); ++k) {
    const PriorAlignmentSummary& geo = summary.components[k].prior_alignment;
    if (geo.aligned) {
      out << "  model " << k << " aligned to its priors: " << geo.num_inliers << " of "
          << geo.num_priors << " priors, RMSE " << std::fixed << std::setprecision(2) << geo.rmse_m
          << " m, " << geo.outliers.size() << " outlier(s)\n";
    } else if (!geo.problem.empty()) {
      out << "  model " << k << " not aligned to its priors: " << geo.problem << "\n";
    }
  }
  if (!summary.prior_outliers.empty()) {
    out << "  pose priors rejected as outliers (" << summary.prior_outliers.size() << "):\n";
    for (size_t k = 0; k < summary.prior_outliers.size() && k < 10; ++k) {
      out << "    " << summary.prior_outliers[k].what << ": " << summary.prior_outliers[k].reason
          << "\n";
    }
    if (summary.prior_outliers.size() > 10) out << "    ... (all in summary.json)\n";
  }
}

void PrintMapperSummary(const MapperSummary& s, const std::string& output_path, std::ostream& out) {
  out << "\nramap mapper: " << s.num_registered_images << " of " << s.num_images
      << " images registered in " << s.components.size() << " model(s), " << std::fixed
      << std::setprecision(2) << s.total_seconds << " s, peak memory " << std::setprecision(0)
      << s.peak_rss_mib << " MiB -> " << output_path << "\n";
  out << "  model  images  points  reproj(px)  rot.edges  pruned  certified\n";
  for (size_t k = 0; k < s.components.size(); ++k) {
    const MapperComponentSummary& c = s.components[k];
    out << std::setw(7) << k << std::setw(8) << c.num_images << std::setw(8) << c.num_points
        << std::setw(12) << std::setprecision(3) << c.mean_reprojection_error_px << std::setw(11)
        << c.num_rotation_edges << std::setw(8) << c.num_pruned_edges << std::setw(11)
        << (c.rotation_certified ? "yes" : "no") << "\n";
  }
  PrintPriorAlignment(s, out);
  // Focal lengths the database did not know, and every camera BA changed.
  for (const CameraIntrinsicsSummary& camera : s.cameras) {
    const CameraCalibration& estimate = camera.view_graph;
    const bool changed = !camera.final_params.empty() && camera.final_params != camera.prior_params;
    if (estimate.camera_id == 0 && !changed) continue;
    out << "  camera " << camera.camera_id << " (" << camera.model << "): focal "
        << std::setprecision(1) << camera.prior_params[0];
    if (estimate.camera_id != 0) {
      out << (estimate.estimated
                  ? " -> " + std::to_string(std::lround(estimate.estimated_focal_px)) +
                        " (view graph, " + std::to_string(estimate.num_pairs) + " pairs)"
                  : " kept (view graph: " + estimate.problem + ")");
    }
    if (changed) out << " -> " << camera.final_params[0] << " (written)";
    out << "\n";
  }
  if (!s.dropped_images.empty()) {
    out << "  not registered (" << s.dropped_images.size() << "):\n";
    for (size_t k = 0; k < s.dropped_images.size() && k < 10; ++k) {
      out << "    " << s.dropped_images[k].what << ": " << s.dropped_images[k].reason << "\n";
    }
    if (s.dropped_images.size() > 10) out << "    ... (all in summary.json)\n";
  }
}

}  // namespace ramap::cli
