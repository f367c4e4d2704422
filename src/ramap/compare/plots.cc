#include "ramap/compare/plots.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "ramap/util/error.h"
#include "ramap/util/image_codecs.h"
#include "ramap/util/staged_output.h"

namespace ramap {
namespace {

constexpr int kWidth = 900;
constexpr int kHeight = 640;
constexpr int kMarginLeft = 80, kMarginRight = 30, kMarginTop = 50, kMarginBottom = 60;
const cv::Scalar kWhite(255, 255, 255), kBlack(0, 0, 0), kGrey(200, 200, 200);

// Colours of the stages in a time plot (BGR), distinct from one another: enough for ramap's
// stages and GLOMAP's in one figure.
cv::Scalar StageColor(size_t k) {
  static const cv::Scalar colors[] = {
      {180, 119, 31}, {14, 127, 255},  {44, 160, 44},   {40, 39, 214},  {189, 103, 148},
      {75, 86, 140},  {194, 119, 227}, {127, 127, 127}, {34, 189, 188}, {207, 190, 23},
      {128, 0, 0},    {0, 128, 128},   {128, 128, 0},   {0, 215, 255},  {60, 20, 120}};
  return colors[k % (sizeof(colors) / sizeof(colors[0]))];
}

// Distinct colours (BGR), the first for the reference series.
cv::Scalar SeriesColor(size_t k) {
  static const cv::Scalar colors[] = {{40, 40, 40},  {0, 110, 230},  {200, 120, 0},
                                      {60, 170, 60}, {160, 60, 170}, {0, 190, 220}};
  return colors[k % (sizeof(colors) / sizeof(colors[0]))];
}

std::string Number(double value) {
  std::ostringstream out;
  out << std::setprecision(3) << value;
  return out.str();
}

void Text(cv::Mat& image, const std::string& text, cv::Point at, double scale = 0.5,
          const cv::Scalar& color = kBlack) {
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, color, 1, cv::LINE_AA);
}

// Maps data coordinates into the plot area.
struct Axes {
  double x0, x1, y0, y1;
  cv::Point ToPixel(double x, double y) const {
    const double u = (x - x0) / (x1 - x0), v = (y - y0) / (y1 - y0);
    return {kMarginLeft + static_cast<int>(std::lround(u * (kWidth - kMarginLeft - kMarginRight))),
            kHeight - kMarginBottom -
                static_cast<int>(std::lround(v * (kHeight - kMarginTop - kMarginBottom)))};
  }
};

// A "nice" tick step for a range: 1, 2 or 5 times a power of ten, about five ticks.
double TickStep(double range) {
  const double raw = range / 5.0;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * power >= raw) return m * power;
  }
  return 10.0 * power;
}

cv::Mat Canvas(const std::string& title) {
  cv::Mat image(kHeight, kWidth, CV_8UC3, kWhite);
  Text(image, title, {kMarginLeft, 22}, 0.65);
  return image;
}

void DrawAxes(cv::Mat& image, const Axes& axes, const std::string& x_label,
              const std::string& y_label) {
  const double dx = TickStep(axes.x1 - axes.x0), dy = TickStep(axes.y1 - axes.y0);
  for (double x = std::ceil(axes.x0 / dx) * dx; x <= axes.x1 + 1e-9 * dx; x += dx) {
    cv::line(image, axes.ToPixel(x, axes.y0), axes.ToPixel(x, axes.y1), kGrey, 1);
    const cv::Point p = axes.ToPixel(x, axes.y0);
    Text(image, Number(std::abs(x) < 1e-12 * dx ? 0.0 : x), {p.x - 12, p.y + 20}, 0.45);
  }
  for (double y = std::ceil(axes.y0 / dy) * dy; y <= axes.y1 + 1e-9 * dy; y += dy) {
    cv::line(image, axes.ToPixel(axes.x0, y), axes.ToPixel(axes.x1, y), kGrey, 1);
    const cv::Point p = axes.ToPixel(axes.x0, y);
    Text(image, Number(std::abs(y) < 1e-12 * dy ? 0.0 : y), {8, p.y + 5}, 0.45);
  }
  cv::rectangle(image, axes.ToPixel(axes.x0, axes.y1), axes.ToPixel(axes.x1, axes.y0), kBlack, 1);
  Text(image, x_label, {kWidth / 2 - 60, kHeight - 15});
  Text(image, y_label, {kMarginLeft, kMarginTop - 8});
}

// Series k is drawn in SeriesColor(k + color_offset); the legend sits in the corner at `top_y`.
void DrawLegend(cv::Mat& image, const std::vector<PlotSeries>& series, size_t color_offset,
                int top_y) {
  for (size_t k = 0; k < series.size(); ++k) {
    const cv::Point at(kWidth - kMarginRight - 190, top_y + 22 * static_cast<int>(k));
    cv::line(image, at, at + cv::Point(30, 0), SeriesColor(k + color_offset), 3, cv::LINE_AA);
    Text(image, series[k].label, at + cv::Point(40, 5));
  }
}

void WritePng(const cv::Mat& image, const std::string& path) {
  WriteFileAtomically(
      path,
      [&](std::ostream& out) {
        std::vector<uchar> bytes;
        if (!EncodeImage(".png", image, &bytes)) throw InputError(path, "cannot encode PNG");
        out.write(reinterpret_cast<const char*>(bytes.data()),
                  static_cast<std::streamsize>(bytes.size()));
      },
      /*binary=*/true);
}

}  // namespace

void PlotTrajectories(const std::vector<PlotSeries>& series, const std::string& title,
                      const std::string& path) {
  cv::Mat image = Canvas(title);
  // Principal axes of the reference, so that a drive seen from above looks like a map.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes_3d = Eigen::Matrix3d::Identity();
  if (!series.empty() && series[0].points.size() >= 3) {
    for (const Eigen::Vector3d& p : series[0].points) mean += p;
    mean /= static_cast<double>(series[0].points.size());
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (const Eigen::Vector3d& p : series[0].points) {
      covariance += (p - mean) * (p - mean).transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
    axes_3d = solver.eigenvectors().rowwise().reverse();  // largest variance first
  }
  std::vector<std::vector<Eigen::Vector2d>> projected(series.size());
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (size_t k = 0; k < series.size(); ++k) {
    for (const Eigen::Vector3d& p : series[k].points) {
      const Eigen::Vector2d q((p - mean).dot(axes_3d.col(0)), (p - mean).dot(axes_3d.col(1)));
      projected[k].push_back(q);
      x0 = std::min(x0, q.x()), x1 = std::max(x1, q.x());
      y0 = std::min(y0, q.y()), y1 = std::max(y1, q.y());
    }
  }
  if (!std::isfinite(x0)) x0 = y0 = -1, x1 = y1 = 1;
  // Equal scale on both axes, with a margin.
  const double plot_w = kWidth - kMarginLeft - kMarginRight;
  const double plot_h = kHeight - kMarginTop - kMarginBottom;
  double span = std::max({(x1 - x0) / plot_w, (y1 - y0) / plot_h, 1e-9}) * 1.1;
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  const Axes axes{cx - 0.5 * span * plot_w, cx + 0.5 * span * plot_w, cy - 0.5 * span * plot_h,
                  cy + 0.5 * span * plot_h};
  DrawAxes(image, axes, "first principal axis (ground-truth units)", "second principal axis");
  for (size_t k = 0; k < series.size(); ++k) {
    std::vector<cv::Point> polyline;
    for (const Eigen::Vector2d& q : projected[k]) polyline.push_back(axes.ToPixel(q.x(), q.y()));
    if (polyline.size() >= 2) {
      cv::polylines(image, polyline, false, SeriesColor(k), k == 0 ? 3 : 2, cv::LINE_AA);
    }
    for (const cv::Point& p : polyline) cv::circle(image, p, 2, SeriesColor(k), -1, cv::LINE_AA);
  }
  DrawLegend(image, series, 0, kMarginTop + 20);
  WritePng(image, path);
}

void PlotCumulativeDistributions(const std::vector<PlotSeries>& series, const std::string& title,
                                 const std::string& x_label, const std::string& path) {
  cv::Mat image = Canvas(title);
  double x1 = 0;
  for (const PlotSeries& s : series) {
    for (const double v : s.values) {
      if (std::isfinite(v)) x1 = std::max(x1, v);
    }
  }
  if (!(x1 > 0)) x1 = 1;
  const Axes axes{0.0, x1 * 1.05, 0.0, 1.0};
  DrawAxes(image, axes, x_label, "fraction of images");
  for (size_t k = 0; k < series.size(); ++k) {
    std::vector<double> values = series[k].values;
    std::sort(values.begin(), values.end());
    std::vector<cv::Point> steps{axes.ToPixel(0, 0)};
    for (size_t i = 0; i < values.size() && std::isfinite(values[i]); ++i) {
      const double before = static_cast<double>(i) / values.size();
      const double after = static_cast<double>(i + 1) / values.size();
      steps.push_back(axes.ToPixel(values[i], before));
      steps.push_back(axes.ToPixel(values[i], after));
    }
    if (!values.empty()) {
      const cv::Point last = steps.back();
      steps.push_back({axes.ToPixel(axes.x1, 0).x, last.y});
    }
    cv::polylines(image, steps, false, SeriesColor(k + 1), 2, cv::LINE_AA);
  }
  // Colours as in the trajectory plot, whose first series is the reference.
  DrawLegend(image, series, 1, kHeight - kMarginBottom - 20 - 22 * static_cast<int>(series.size()));
  WritePng(image, path);
}

void PlotStageTimes(const std::vector<StageBar>& bars, const std::string& title,
                    const std::string& path) {
  cv::Mat image = Canvas(title);
  double longest = 0;
  std::vector<std::string> stage_names;
  for (const StageBar& bar : bars) {
    double total = 0;
    for (const auto& [name, seconds] : bar.stages) {
      total += seconds;
      if (std::find(stage_names.begin(), stage_names.end(), name) == stage_names.end()) {
        stage_names.push_back(name);
      }
    }
    longest = std::max(longest, total);
  }
  if (!(longest > 0)) longest = 1;
  const int left = 170, right = kWidth - 40, top = kMarginTop + 10;
  const int bar_height = 36, gap = 24;
  const double px_per_second = (right - left) / (longest * 1.05);
  for (size_t b = 0; b < bars.size(); ++b) {
    const int y = top + static_cast<int>(b) * (bar_height + gap);
    Text(image, bars[b].label, {10, y + bar_height / 2 + 5});
    double x = left;
    double total = 0;
    for (const auto& [name, seconds] : bars[b].stages) {
      const size_t color =
          std::find(stage_names.begin(), stage_names.end(), name) - stage_names.begin();
      const double w = seconds * px_per_second;
      cv::rectangle(image, cv::Point(static_cast<int>(x), y),
                    cv::Point(static_cast<int>(x + std::max(w, 1.0)), y + bar_height),
                    StageColor(color), -1);
      x += w;
      total += seconds;
    }
    Text(image, Number(total) + " s", {static_cast<int>(x) + 6, y + bar_height / 2 + 5});
  }
  // Legend of the stages, below the bars.
  int legend_y = top + static_cast<int>(bars.size()) * (bar_height + gap) + 10;
  int legend_x = left;
  for (size_t k = 0; k < stage_names.size(); ++k) {
    if (legend_x > kWidth - 200) legend_x = left, legend_y += 24;
    cv::rectangle(image, cv::Point(legend_x, legend_y), cv::Point(legend_x + 16, legend_y + 16),
                  StageColor(k), -1);
    Text(image, stage_names[k], {legend_x + 22, legend_y + 14}, 0.45);
    legend_x += 30 + 9 * static_cast<int>(stage_names[k].size());
  }
  WritePng(image(cv::Rect(0, 0, kWidth, std::min(kHeight, legend_y + 40))), path);
}

}  // namespace ramap
