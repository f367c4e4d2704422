// Figures of a comparison, drawn with OpenCV into PNG files: what a person would rather look at
// than read. Each takes plain data (one series per mapper) and writes one image.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace ramap {

// One mapper's values in a figure.
struct PlotSeries {
  std::string label;
  std::vector<Eigen::Vector3d> points;  // trajectory plots: camera centres, in capture order
  std::vector<double> values;           // distribution plots: one error per image
};

// Top-down view of camera centres: every series projected on the plane of the first series'
// two principal axes (the first series is the reference, e.g. the ground truth), drawn as a line
// through the centres in order. Equal scale on both axes.
void PlotTrajectories(const std::vector<PlotSeries>& series, const std::string& title,
                      const std::string& path);

// Cumulative distribution of each series' values (x: the value, `x_label`; y: fraction of images
// at or below it). Values that are +inf (unregistered images) keep the curve below 1.
void PlotCumulativeDistributions(const std::vector<PlotSeries>& series, const std::string& title,
                                 const std::string& x_label, const std::string& path);

// Horizontal stacked bars, one per row: each row's stage times in seconds.
struct StageBar {
  std::string label;
  std::vector<std::pair<std::string, double>> stages;  // name, seconds
};
void PlotStageTimes(const std::vector<StageBar>& bars, const std::string& title,
                    const std::string& path);

}  // namespace ramap
