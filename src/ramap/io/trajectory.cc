#include "ramap/io/trajectory.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "ramap/io/colmap_model.h"
#include "ramap/util/error.h"
#include "ramap/util/staged_output.h"

namespace ramap {
namespace fs = std::filesystem;

namespace {

// Ground-truth rotations are printed with 6 to 20 digits; 1e-4 accepts every real file we know
// while still catching a transposed, scaled or garbled matrix.
constexpr double kOrthonormalityTolerance = 1e-4;

std::string LineSource(const std::string& path, int line_number) {
  return path + ":" + std::to_string(line_number);
}

// A number that must be all of `token`; nullopt when it is not.
std::optional<double> ParseNumber(const std::string& token) {
  if (token.empty()) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(token.c_str(), &end);
  if (*end != '\0') return std::nullopt;
  return value;
}

std::vector<std::string> Split(const std::string& line) {
  std::vector<std::string> tokens;
  std::istringstream stream(line);
  std::string token;
  while (stream >> token) tokens.push_back(token);
  return tokens;
}

// Reads `count` finite numbers from tokens[first...]; `where` names file and line for errors.
std::vector<double> Numbers(const std::vector<std::string>& tokens, size_t first, size_t count,
                            const std::string& where) {
  std::vector<double> values;
  for (size_t k = first; k < first + count; ++k) {
    const std::optional<double> value = ParseNumber(tokens[k]);
    if (!value) throw InputError(where, "cannot read a number from '" + tokens[k] + "'");
    if (!std::isfinite(*value)) {
      throw InputError(where, "value '" + tokens[k] + "' is not a finite number");
    }
    values.push_back(*value);
  }
  return values;
}

// Checks that R is a rotation to kOrthonormalityTolerance and returns the nearest exact one.
Eigen::Matrix3d CheckedRotation(const Eigen::Matrix3d& R, const std::string& where) {
  const double orthogonality_error =
      (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (orthogonality_error > kOrthonormalityTolerance) {
    throw InputError(where, "rotation matrix is not orthonormal (max |R^T R - I| = " +
                                std::to_string(orthogonality_error) + ")");
  }
  if (std::abs(R.determinant() - 1.0) > kOrthonormalityTolerance) {
    throw InputError(where, "rotation matrix has determinant " + std::to_string(R.determinant()) +
                                ", not +1 (a reflection?)");
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

Rigid3d PoseFromMatrix(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  return Rigid3d(Eigen::Quaterniond(R).normalized(), t);
}

class LineReader {
 public:
  explicit LineReader(const std::string& path) : path_(path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw InputError(path, "file not found");
    file_.open(path);
    if (!file_) throw InputError(path, "cannot open for reading");
  }
  // Next line with content that is not a '#' comment, split into tokens.
  bool Next(std::vector<std::string>* tokens) {
    std::string line;
    while (std::getline(file_, line)) {
      ++line_number_;
      *tokens = Split(line);
      if (!tokens->empty() && (*tokens)[0][0] != '#') return true;
    }
    return false;
  }
  std::string where() const { return LineSource(path_, line_number_); }

 private:
  std::string path_;
  std::ifstream file_;
  int line_number_ = 0;
};

GroundTruth ReadTum(const std::string& path) {
  GroundTruth gt;
  gt.matched_by_index = true;
  gt.has_timestamps = true;
  LineReader in(path);
  std::vector<std::string> t;
  while (in.Next(&t)) {
    if (t.size() != 8) {
      throw InputError(in.where(), "expected 8 values 'timestamp tx ty tz qx qy qz qw', found " +
                                       std::to_string(t.size()));
    }
    const std::vector<double> v = Numbers(t, 0, 8, in.where());
    Eigen::Quaterniond world_from_cam_rotation(v[7], v[4], v[5], v[6]);
    // TUM files print 4 decimals, so a unit quaternion reads back with a norm off by up to ~2e-4;
    // the rotation-matrix tolerance would reject real files.
    const double norm = world_from_cam_rotation.norm();
    if (std::abs(norm - 1.0) > 1e-3) {
      throw InputError(in.where(), "quaternion has norm " + std::to_string(norm) + ", not 1");
    }
    world_from_cam_rotation.normalize();
    const Rigid3d world_from_cam(world_from_cam_rotation, Eigen::Vector3d(v[1], v[2], v[3]));
    GroundTruthPose pose;
    pose.timestamp = v[0];
    pose.cam_from_world = world_from_cam.Inverse();
    gt.poses.push_back(pose);
  }
  return gt;
}

GroundTruth ReadKitti(const std::string& path) {
  GroundTruth gt;
  gt.matched_by_index = true;
  LineReader in(path);
  std::vector<std::string> t;
  while (in.Next(&t)) {
    if (t.size() != 12) {
      throw InputError(in.where(), "expected 12 values (3x4 matrix, row-major), found " +
                                       std::to_string(t.size()));
    }
    const std::vector<double> v = Numbers(t, 0, 12, in.where());
    Eigen::Matrix3d R;
    Eigen::Vector3d c;
    for (int r = 0; r < 3; ++r) {
      for (int col = 0; col < 3; ++col) R(r, col) = v[4 * r + col];
      c[r] = v[4 * r + 3];
    }
    // The file holds world_from_cam = [R | c].
    const Eigen::Matrix3d world_from_cam = CheckedRotation(R, in.where());
    GroundTruthPose pose;
    pose.cam_from_world =
        PoseFromMatrix(world_from_cam.transpose(), -world_from_cam.transpose() * c);
    gt.poses.push_back(pose);
  }
  return gt;
}

GroundTruth ReadStrecha(const std::string& path) {
  std::error_code ec;
  if (!fs::is_directory(path, ec)) {
    throw InputError(path, "not a folder (expected gt_dense_cameras with NAME.camera files)");
  }
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(path)) {
    if (entry.is_regular_file() && entry.path().extension() == ".camera") {
      files.push_back(entry.path());
    }
  }
  if (files.empty()) throw InputError(path, "no .camera files");
  std::sort(files.begin(), files.end());
  GroundTruth gt;
  for (const fs::path& file : files) {
    // Nine lines: K (3), distortion (1), R camera-to-world (3), centre C (1), width height (1).
    LineReader in(file.string());
    std::vector<std::vector<std::string>> lines(9);
    const size_t expected_sizes[9] = {3, 3, 3, 0, 3, 3, 3, 3, 2};
    for (int k = 0; k < 9; ++k) {
      if (!in.Next(&lines[k])) {
        throw InputError(file.string(), "ends after " + std::to_string(k) +
                                            " lines; a .camera file has 9 (K, distortion, R, C, "
                                            "size)");
      }
      if (expected_sizes[k] != 0 && lines[k].size() != expected_sizes[k]) {
        throw InputError(in.where(), "expected " + std::to_string(expected_sizes[k]) +
                                         " values, found " + std::to_string(lines[k].size()));
      }
      Numbers(lines[k], 0, lines[k].size(), in.where());
    }
    Eigen::Matrix3d R;
    for (int r = 0; r < 3; ++r) {
      const std::vector<double> row = Numbers(lines[4 + r], 0, 3, LineSource(file.string(), 5 + r));
      for (int col = 0; col < 3; ++col) R(r, col) = row[col];
    }
    const std::vector<double> c = Numbers(lines[7], 0, 3, LineSource(file.string(), 8));
    const Eigen::Matrix3d world_from_cam = CheckedRotation(R, file.string() + ":5-7");
    const Eigen::Vector3d centre(c[0], c[1], c[2]);
    GroundTruthPose pose;
    pose.image_name = file.stem().string();  // "0000.jpg.camera" -> "0000.jpg"
    pose.cam_from_world =
        PoseFromMatrix(world_from_cam.transpose(), -world_from_cam.transpose() * centre);
    gt.poses.push_back(pose);
  }
  return gt;
}

GroundTruth ReadMiddlebury(const std::string& path) {
  LineReader in(path);
  std::vector<std::string> t;
  if (!in.Next(&t)) throw InputError(path, "empty file (expected the number of images first)");
  if (t.size() != 1) throw InputError(in.where(), "expected the number of images alone");
  const std::string count_text = t[0];
  const std::optional<double> count = ParseNumber(count_text);
  if (!count || *count < 0 || *count != std::floor(*count)) {
    throw InputError(in.where(), "cannot read the number of images from '" + count_text + "'");
  }
  GroundTruth gt;
  while (in.Next(&t)) {
    if (t.size() != 22) {
      throw InputError(in.where(),
                       "expected 'name k11..k33 r11..r33 t1 t2 t3' (22 fields), found " +
                           std::to_string(t.size()));
    }
    const std::vector<double> v = Numbers(t, 1, 21, in.where());
    Eigen::Matrix3d R;
    for (int r = 0; r < 3; ++r) {
      for (int col = 0; col < 3; ++col) R(r, col) = v[9 + 3 * r + col];
    }
    GroundTruthPose pose;
    pose.image_name = t[0];
    // P = K [R | t]: already world-to-camera.
    pose.cam_from_world =
        PoseFromMatrix(CheckedRotation(R, in.where()), Eigen::Vector3d(v[18], v[19], v[20]));
    gt.poses.push_back(pose);
  }
  // Compared as doubles: a count past size_t's range (a corrupt header) must not be cast.
  if (static_cast<double>(gt.poses.size()) != *count) {
    throw InputError(
        path, "announces " + count_text + " images but lists " + std::to_string(gt.poses.size()));
  }
  return gt;
}

GroundTruth ReadColmapReference(const std::string& path) {
  const Reconstruction model = ReadColmapModel(path);
  GroundTruth gt;
  for (const auto& [image_id, image] : model.images) {
    GroundTruthPose pose;
    pose.image_name = image.name;
    const Eigen::Matrix3d R =
        CheckedRotation(image.cam_from_world.rotation.normalized().toRotationMatrix(),
                        path + " (image '" + image.name + "')");
    pose.cam_from_world = PoseFromMatrix(R, image.cam_from_world.translation);
    gt.poses.push_back(pose);
  }
  std::sort(gt.poses.begin(), gt.poses.end(),
            [](const GroundTruthPose& a, const GroundTruthPose& b) {
              return a.image_name < b.image_name;
            });
  return gt;
}

// The number an image name stands for: its name minus the extension, read whole.
std::optional<double> NameNumber(const std::string& name) {
  return ParseNumber(fs::path(name).stem().string());
}

std::string FormatDouble(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof(buffer), "%.17g", value);
  return buffer;
}

}  // namespace

GroundTruthFormat GroundTruthFormatFromName(const std::string& name) {
  if (name == "tum") return GroundTruthFormat::kTum;
  if (name == "kitti") return GroundTruthFormat::kKitti;
  if (name == "strecha") return GroundTruthFormat::kStrecha;
  if (name == "middlebury") return GroundTruthFormat::kMiddlebury;
  if (name == "colmap") return GroundTruthFormat::kColmap;
  throw InputError(
      "--ground_truth_format",
      "unknown format '" + name + "' (known: tum, kitti, strecha, middlebury, colmap)");
}

namespace {

GroundTruth ReadGroundTruthOfFormat(const std::string& path, GroundTruthFormat format) {
  switch (format) {
    case GroundTruthFormat::kTum:
      return ReadTum(path);
    case GroundTruthFormat::kKitti:
      return ReadKitti(path);
    case GroundTruthFormat::kStrecha:
      return ReadStrecha(path);
    case GroundTruthFormat::kMiddlebury:
      return ReadMiddlebury(path);
    case GroundTruthFormat::kColmap:
      return ReadColmapReference(path);
  }
  throw InputError(path, "unknown ground truth format");
}

// Pose k for the image numbered k (KITTI's 000042.png), when every name is a frame number within
// the poses; empty otherwise.
std::map<std::string, Rigid3d> ByFrameNumber(const GroundTruth& ground_truth,
                                             const std::vector<std::string>& image_names) {
  std::map<std::string, Rigid3d> result;
  for (const std::string& name : image_names) {
    const std::optional<double> number = NameNumber(name);
    if (!number || *number < 0 || *number != std::floor(*number) ||
        *number >= static_cast<double>(ground_truth.poses.size())) {
      return {};
    }
    result.emplace(name, ground_truth.poses[static_cast<size_t>(*number)].cam_from_world);
  }
  return result;
}

}  // namespace

GroundTruth ReadGroundTruth(const std::string& path, GroundTruthFormat format) {
  GroundTruth ground_truth = ReadGroundTruthOfFormat(path, format);
  ground_truth.source = path;
  return ground_truth;
}

std::map<std::string, Rigid3d> GroundTruthByImageName(const GroundTruth& ground_truth,
                                                      std::vector<std::string> image_names) {
  std::sort(image_names.begin(), image_names.end());
  std::map<std::string, Rigid3d> result;
  if (!ground_truth.matched_by_index) {
    std::map<std::string, const Rigid3d*> by_name;
    for (const GroundTruthPose& pose : ground_truth.poses)
      by_name[pose.image_name] = &pose.cam_from_world;
    for (const std::string& name : image_names) {
      const auto it = by_name.find(name);
      if (it != by_name.end()) result.emplace(name, *it->second);
    }
    return result;
  }
  if (ground_truth.has_timestamps && !image_names.empty()) {
    std::vector<std::pair<double, const Rigid3d*>> by_time;
    for (const GroundTruthPose& pose : ground_truth.poses) {
      by_time.emplace_back(pose.timestamp, &pose.cam_from_world);
    }
    std::sort(by_time.begin(), by_time.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    std::map<std::string, Rigid3d> matched;
    for (const std::string& name : image_names) {
      const std::optional<double> number = NameNumber(name);
      if (!number) break;
      const auto it = std::lower_bound(by_time.begin(), by_time.end(), *number - 1e-6,
                                       [](const auto& a, double t) { return a.first < t; });
      if (it == by_time.end() || it->first > *number + 1e-6) break;
      matched.emplace(name, *it->second);
    }
    if (matched.size() == image_names.size()) return matched;
  }
  if (ground_truth.poses.size() != image_names.size()) {
    // A subset of a sequence is matched by its frame numbers; anything else would pair poses with
    // the wrong images without a word.
    std::map<std::string, Rigid3d> numbered = ByFrameNumber(ground_truth, image_names);
    if (!numbered.empty() || image_names.empty()) return numbered;
    throw InputError(ground_truth.source,
                     "poses are matched to images by index, but it has " +
                         std::to_string(ground_truth.poses.size()) + " poses for " +
                         std::to_string(image_names.size()) +
                         " images whose names are not all frame numbers within the poses "
                         "(give as many poses as images, or name the images 000000.png, ...)");
  }
  for (size_t i = 0; i < image_names.size(); ++i) {
    result.emplace(image_names[i], ground_truth.poses[i].cam_from_world);
  }
  return result;
}

void WriteTumTrajectory(const Reconstruction& reconstruction, const std::string& path) {
  std::vector<const Image*> images;
  for (const auto& [image_id, image] : reconstruction.images) images.push_back(&image);
  std::sort(images.begin(), images.end(),
            [](const Image* a, const Image* b) { return a->name < b->name; });
  bool all_numbered = true;
  for (const Image* image : images) all_numbered &= NameNumber(image->name).has_value();
  for (const Image* image : images) {
    if (!image->cam_from_world.rotation.coeffs().allFinite() ||
        !image->cam_from_world.translation.allFinite()) {
      throw InputError(path, "image '" + image->name + "' has a NaN or infinite pose");
    }
  }
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "# ramap trajectory: timestamp tx ty tz qx qy qz qw (camera-to-world)\n";
    for (size_t i = 0; i < images.size(); ++i) {
      const double timestamp = all_numbered ? *NameNumber(images[i]->name) : static_cast<double>(i);
      const Rigid3d world_from_cam = images[i]->cam_from_world.Inverse();
      const Eigen::Quaterniond q = world_from_cam.rotation.normalized();
      const Eigen::Vector3d& c = world_from_cam.translation;
      out << FormatDouble(timestamp) << " " << FormatDouble(c.x()) << " " << FormatDouble(c.y())
          << " " << FormatDouble(c.z()) << " " << FormatDouble(q.x()) << " " << FormatDouble(q.y())
          << " " << FormatDouble(q.z()) << " " << FormatDouble(q.w()) << "\n";
    }
  });
}

void WriteColmapModelAndTrajectory(const Reconstruction& reconstruction, const std::string& path,
                                   ModelFormat format) {
  const std::string trajectory = (std::filesystem::path(path) / "trajectory_tum.txt").string();
  std::error_code ec;
  const bool had_trajectory = std::filesystem::is_regular_file(trajectory, ec);
  WriteColmapModel(reconstruction, path, format);
  if (had_trajectory) WriteTumTrajectory(reconstruction, trajectory);
}

}  // namespace ramap
