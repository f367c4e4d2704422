#include "ramap/io/colmap_model.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "ramap/io/colmap_model_rigs.h"
#include "ramap/io/model_file_io.h"
#include "ramap/util/error.h"
#include "ramap/util/staged_output.h"

namespace ramap {
namespace fs = std::filesystem;

namespace {

// Where each of the three files of a model is (or will be): used in every error message.
struct ModelFiles {
  std::string cameras;
  std::string images;
  std::string points3D;
};

ModelFiles FilesIn(const std::string& folder, const std::string& extension) {
  const fs::path dir(folder);
  return {(dir / ("cameras" + extension)).string(), (dir / ("images" + extension)).string(),
          (dir / ("points3D" + extension)).string()};
}

std::string ImageLabel(const Image& image) {
  return "image " + std::to_string(image.image_id) + " ('" + image.name + "')";
}

// ---------------------------------------------------------------------------------------------
// Checks shared by readers (after parsing) and the writer (before writing anything).

void CheckCamera(const Camera& camera, const std::string& source, const std::string& label) {
  const int expected = NumCameraParams(camera.model);
  if (static_cast<int>(camera.params.size()) != expected) {
    throw InputError(source, label + ": model " + CameraModelName(camera.model) + " takes " +
                                 std::to_string(expected) + " parameters, found " +
                                 std::to_string(camera.params.size()));
  }
  for (size_t i = 0; i < camera.params.size(); ++i) {
    if (!std::isfinite(camera.params[i])) {
      throw InputError(source,
                       label + ": parameter " + std::to_string(i + 1) + " is not a finite number");
    }
  }
  if (camera.width == 0 || camera.height == 0) {
    throw InputError(source, label + ": image size " + std::to_string(camera.width) + "x" +
                                 std::to_string(camera.height) + " is empty");
  }
}

void CheckPose(const Rigid3d& pose, const std::string& source, const std::string& label) {
  const Eigen::Vector4d q = pose.rotation.coeffs();
  if (!q.allFinite() || !pose.translation.allFinite()) {
    throw InputError(source, label + ": pose has a NaN or infinite value");
  }
  // COLMAP writes unit quaternions; anything far from unit length is a corrupt value, not
  // rounding. The stored value is kept as is so that files pass through bit-identically.
  if (std::abs(q.norm() - 1.0) > 1e-2) {
    throw InputError(
        source, label + ": rotation quaternion has norm " + std::to_string(q.norm()) + ", not 1");
  }
}

void CheckPoint(const Point3D& point, const std::string& source, const std::string& label) {
  if (!point.xyz.allFinite()) {
    throw InputError(source, label + ": position has a NaN or infinite value");
  }
  if (std::isnan(point.error)) throw InputError(source, label + ": error is NaN");
}

// Ids, values, and each image's camera.
void CheckCamerasAndImages(const Reconstruction& model, const ModelFiles& files) {
  for (const auto& [camera_id, camera] : model.cameras) {
    const std::string label = "camera " + std::to_string(camera_id);
    if (camera.camera_id != camera_id) {
      throw InputError(files.cameras,
                       label + " holds the mismatching id " + std::to_string(camera.camera_id));
    }
    CheckCamera(camera, files.cameras, label);
  }
  for (const auto& [image_id, image] : model.images) {
    const std::string label = ImageLabel(image);
    if (image.image_id != image_id) {
      throw InputError(files.images,
                       label + " is held under the mismatching id " + std::to_string(image_id));
    }
    CheckPose(image.cam_from_world, files.images, label);
    if (model.cameras.count(image.camera_id) == 0) {
      throw InputError(files.images, label + " uses camera " + std::to_string(image.camera_id) +
                                         ", which " + fs::path(files.cameras).filename().string() +
                                         " does not have");
    }
    for (size_t idx = 0; idx < image.points2D.size(); ++idx) {
      const Point2D& point2D = image.points2D[idx];
      if (!point2D.xy.allFinite()) {
        throw InputError(files.images, label + " point2D " + std::to_string(idx) +
                                           " has a NaN or infinite coordinate");
      }
    }
  }
}

// Each 3D point's values, and that every track element names an image point that names it back.
void CheckTracks(const Reconstruction& model, const ModelFiles& files) {
  for (const auto& [point3D_id, point] : model.points3D) {
    const std::string label = "3D point " + std::to_string(point3D_id);
    CheckPoint(point, files.points3D, label);
    for (size_t k = 0; k < point.track.size(); ++k) {
      const TrackElement& element = point.track[k];
      // Labels are built only for the message: building one per element was a noticeable part
      // of checking a long drive's model.
      const auto where = [&] {
        return label + " track element " + std::to_string(k + 1) + " (image " +
               std::to_string(element.image_id) + ", point2D " +
               std::to_string(element.point2D_idx) + ")";
      };
      const auto it = model.images.find(element.image_id);
      if (it == model.images.end()) {
        throw InputError(files.points3D, where() + " names an image that " +
                                             fs::path(files.images).filename().string() +
                                             " does not have");
      }
      if (element.point2D_idx >= it->second.points2D.size()) {
        throw InputError(files.points3D, where() + ": point2D index out of range, the image has " +
                                             std::to_string(it->second.points2D.size()) +
                                             " points");
      }
      if (it->second.points2D[element.point2D_idx].point3D_id != point3D_id) {
        throw InputError(files.points3D,
                         where() + ": that image point does not name this 3D point back");
      }
    }
  }
}

// Every image point naming a 3D point is listed in that point's track.
void CheckImagePointReferences(const Reconstruction& model, const ModelFiles& files) {
  for (const auto& [image_id, image] : model.images) {
    const std::string label = ImageLabel(image);
    for (size_t idx = 0; idx < image.points2D.size(); ++idx) {
      const Point2D& point2D = image.points2D[idx];
      if (point2D.point3D_id == kInvalidPoint3DId) continue;
      const auto it = model.points3D.find(point2D.point3D_id);
      const auto where = [&] {
        return label + " point2D " + std::to_string(idx) + " names 3D point " +
               std::to_string(point2D.point3D_id);
      };
      if (it == model.points3D.end()) {
        throw InputError(
            files.images,
            where() + ", which " + fs::path(files.points3D).filename().string() + " does not have");
      }
      bool listed = false;
      for (const TrackElement& element : it->second.track) {
        listed |= element.image_id == image_id && element.point2D_idx == idx;
      }
      if (!listed) {
        throw InputError(files.images, where() + ", whose track does not list this observation");
      }
    }
  }
}

// Every cross reference of the model: cameras of images, 3D points of image points, images and
// point2D indices of tracks, and that both sides agree.
void CheckModel(const Reconstruction& model, const ModelFiles& files) {
  CheckCamerasAndImages(model, files);
  CheckTracks(model, files);
  // Image points last, so that a broken track is reported as such rather than as its echo.
  CheckImagePointReferences(model, files);
}

// ---------------------------------------------------------------------------------------------
// Binary format: little-endian, fields as in COLMAP 3.8 (src/base/reconstruction.cc).

void ReadCamerasBinary(const std::string& path, Reconstruction* model) {
  BinaryReader in(path);
  in.SetItem("the number of cameras");
  const uint64_t count = in.ReadUint64();
  for (uint64_t i = 0; i < count; ++i) {
    const std::string item = "camera " + Ordinal(i, count);
    in.SetItem(item);
    Camera camera;
    camera.camera_id = in.ReadUint32();
    const int32_t model_id = in.ReadInt32();
    const std::optional<CameraModel> camera_model = CameraModelFromId(model_id);
    if (!camera_model) {
      throw InputError(path, item + " (id " + std::to_string(camera.camera_id) +
                                 "): unknown camera model id " + std::to_string(model_id));
    }
    camera.model = *camera_model;
    camera.width = in.ReadUint64();
    camera.height = in.ReadUint64();
    camera.params.resize(NumCameraParams(camera.model));
    for (double& param : camera.params) param = in.ReadDouble();
    if (!model->cameras.emplace(camera.camera_id, camera).second) {
      throw InputError(path, item + ": duplicate camera id " + std::to_string(camera.camera_id));
    }
  }
  in.ExpectEnd();
}

void ReadImagesBinary(const std::string& path, Reconstruction* model) {
  BinaryReader in(path);
  in.SetItem("the number of images");
  const uint64_t count = in.ReadUint64();
  for (uint64_t i = 0; i < count; ++i) {
    const std::string item = "image " + Ordinal(i, count);
    in.SetItem(item);
    Image image;
    image.image_id = in.ReadUint32();
    const double qw = in.ReadDouble();
    const double qx = in.ReadDouble();
    const double qy = in.ReadDouble();
    const double qz = in.ReadDouble();
    image.cam_from_world.rotation = Eigen::Quaterniond(qw, qx, qy, qz);
    for (int k = 0; k < 3; ++k) image.cam_from_world.translation[k] = in.ReadDouble();
    image.camera_id = in.ReadUint32();
    image.name = in.ReadString();
    const uint64_t num_points2D = in.ReadUint64();
    in.ExpectRecords(num_points2D, 3 * 8);
    image.points2D.resize(num_points2D);
    for (Point2D& point2D : image.points2D) {
      point2D.xy.x() = in.ReadDouble();
      point2D.xy.y() = in.ReadDouble();
      point2D.point3D_id = in.ReadUint64();
    }
    if (model->images.count(image.image_id) != 0) {
      throw InputError(path, item + ": duplicate image id " + std::to_string(image.image_id));
    }
    model->images.emplace(image.image_id, std::move(image));
  }
  in.ExpectEnd();
}

void ReadPoints3DBinary(const std::string& path, Reconstruction* model) {
  BinaryReader in(path);
  in.SetItem("the number of 3D points");
  const uint64_t count = in.ReadUint64();
  for (uint64_t i = 0; i < count; ++i) {
    const std::string item = "3D point " + Ordinal(i, count);
    in.SetItem(item);
    const uint64_t point3D_id = in.ReadUint64();
    Point3D point;
    for (int k = 0; k < 3; ++k) point.xyz[k] = in.ReadDouble();
    for (int k = 0; k < 3; ++k) point.color[k] = in.ReadUint8();
    point.error = in.ReadDouble();
    const uint64_t track_length = in.ReadUint64();
    in.ExpectRecords(track_length, 8);
    point.track.resize(track_length);
    for (TrackElement& element : point.track) {
      element.image_id = in.ReadUint32();
      element.point2D_idx = in.ReadUint32();
    }
    if (model->points3D.count(point3D_id) != 0) {
      throw InputError(path, item + ": duplicate 3D point id " + std::to_string(point3D_id));
    }
    model->points3D.emplace(point3D_id, std::move(point));
  }
  in.ExpectEnd();
}

void ReadCamerasText(const std::string& path, Reconstruction* model) {
  TextLines in(path);
  std::vector<std::string> t;
  while (in.NextDataLine(&t)) {
    if (t.size() < 4) in.Fail("expected CAMERA_ID MODEL WIDTH HEIGHT PARAMS[]");
    Camera camera;
    camera.camera_id = static_cast<uint32_t>(in.Unsigned(t[0], "the camera id", kMaxUint32));
    const std::string label = "camera " + t[0];
    const std::optional<CameraModel> camera_model = CameraModelFromName(t[1]);
    if (!camera_model) in.Fail(label + ": unknown camera model '" + t[1] + "'");
    camera.model = *camera_model;
    camera.width = in.Unsigned(t[2], "the width of " + label, kMaxUint64);
    camera.height = in.Unsigned(t[3], "the height of " + label, kMaxUint64);
    const size_t expected = NumCameraParams(camera.model);
    if (t.size() - 4 != expected) {
      in.Fail(label + ": model " + t[1] + " takes " + std::to_string(expected) +
              " parameters, found " + std::to_string(t.size() - 4));
    }
    for (size_t k = 0; k < expected; ++k) {
      camera.params.push_back(
          in.FiniteDouble(t[4 + k], "parameter " + std::to_string(k + 1) + " of " + label));
    }
    if (!model->cameras.emplace(camera.camera_id, camera).second) {
      in.Fail("duplicate camera id " + t[0]);
    }
  }
}

void ReadImagesText(const std::string& path, Reconstruction* model) {
  TextLines in(path);
  std::vector<std::string> t;
  while (in.NextDataLine(&t)) {
    if (t.size() != 10) {
      in.Fail("expected IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME (10 fields), found " +
              std::to_string(t.size()) + " fields");
    }
    Image image;
    image.image_id = static_cast<uint32_t>(in.Unsigned(t[0], "the image id", kMaxUint32));
    const std::string label = "image " + t[0];
    double q[4];
    for (int k = 0; k < 4; ++k) q[k] = in.FiniteDouble(t[1 + k], "the rotation of " + label);
    image.cam_from_world.rotation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
    for (int k = 0; k < 3; ++k) {
      image.cam_from_world.translation[k] =
          in.FiniteDouble(t[5 + k], "the translation of " + label);
    }
    image.camera_id =
        static_cast<uint32_t>(in.Unsigned(t[8], "the camera id of " + label, kMaxUint32));
    image.name = t[9];
    const int image_line = in.line_number();
    if (!in.NextRawLine(&t)) {
      in.Fail(label + " (line " + std::to_string(image_line) +
              ") has no line of observations after it");
    }
    if (t.size() % 3 != 0) {
      in.Fail("observations of " + label + " are not triples X Y POINT3D_ID (" +
              std::to_string(t.size()) + " fields)");
    }
    image.points2D.resize(t.size() / 3);
    for (size_t idx = 0; idx < image.points2D.size(); ++idx) {
      Point2D& point2D = image.points2D[idx];
      const std::string what = "point2D " + std::to_string(idx) + " of " + label;
      point2D.xy.x() = in.FiniteDouble(t[3 * idx], "x of " + what);
      point2D.xy.y() = in.FiniteDouble(t[3 * idx + 1], "y of " + what);
      const std::string& id = t[3 * idx + 2];
      point2D.point3D_id = id == "-1" ? kInvalidPoint3DId
                                      : in.Unsigned(id, "the 3D point id of " + what, kMaxUint64);
    }
    if (model->images.count(image.image_id) != 0) {
      in.Fail("duplicate image id " + std::to_string(image.image_id));
    }
    model->images.emplace(image.image_id, std::move(image));
  }
}

void ReadPoints3DText(const std::string& path, Reconstruction* model) {
  TextLines in(path);
  std::vector<std::string> t;
  while (in.NextDataLine(&t)) {
    if (t.size() < 8 || (t.size() - 8) % 2 != 0) {
      in.Fail("expected POINT3D_ID X Y Z R G B ERROR then (IMAGE_ID POINT2D_IDX) pairs, found " +
              std::to_string(t.size()) + " fields");
    }
    const uint64_t point3D_id = in.Unsigned(t[0], "the 3D point id", kMaxUint64);
    const std::string label = "3D point " + t[0];
    Point3D point;
    for (int k = 0; k < 3; ++k)
      point.xyz[k] = in.FiniteDouble(t[1 + k], "the position of " + label);
    for (int k = 0; k < 3; ++k) {
      point.color[k] = static_cast<uint8_t>(in.Unsigned(t[4 + k], "the colour of " + label, 255));
    }
    point.error = in.Double(t[7], "the error of " + label);
    if (std::isnan(point.error)) in.Fail("the error of " + label + " is NaN");
    point.track.resize((t.size() - 8) / 2);
    for (size_t k = 0; k < point.track.size(); ++k) {
      const std::string what = "track element " + std::to_string(k + 1) + " of " + label;
      point.track[k].image_id =
          static_cast<uint32_t>(in.Unsigned(t[8 + 2 * k], "the image id of " + what, kMaxUint32));
      point.track[k].point2D_idx = static_cast<uint32_t>(
          in.Unsigned(t[9 + 2 * k], "the point2D index of " + what, kMaxUint32));
    }
    if (model->points3D.count(point3D_id) != 0) in.Fail("duplicate 3D point id " + t[0]);
    model->points3D.emplace(point3D_id, std::move(point));
  }
}

size_t NumObservations(const Reconstruction& model) {
  size_t count = 0;
  for (const auto& [image_id, image] : model.images) {
    for (const Point2D& point2D : image.points2D) count += point2D.point3D_id != kInvalidPoint3DId;
  }
  return count;
}

void WriteCamerasText(const Reconstruction& model, std::ostream& out) {
  out << "# Camera list with one line of data per camera:\n"
         "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
         "# Number of cameras: "
      << model.cameras.size() << "\n";
  for (const auto& [camera_id, camera] : model.cameras) {
    out << camera_id << " " << CameraModelName(camera.model) << " " << camera.width << " "
        << camera.height;
    for (const double param : camera.params) out << " " << FormatDouble(param);
    out << "\n";
  }
}

void WriteImagesText(const Reconstruction& model, std::ostream& out) {
  const double mean_observations =
      model.images.empty() ? 0.0
                           : static_cast<double>(NumObservations(model)) / model.images.size();
  out << "# Image list with two lines of data per image:\n"
         "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
         "#   POINTS2D[] as (X, Y, POINT3D_ID)\n"
         "# Number of images: "
      << model.images.size() << ", mean observations per image: " << FormatDouble(mean_observations)
      << "\n";
  for (const auto& [image_id, image] : model.images) {
    const Eigen::Quaterniond& q = image.cam_from_world.rotation;
    const Eigen::Vector3d& t = image.cam_from_world.translation;
    out << image_id << " " << FormatDouble(q.w()) << " " << FormatDouble(q.x()) << " "
        << FormatDouble(q.y()) << " " << FormatDouble(q.z()) << " " << FormatDouble(t.x()) << " "
        << FormatDouble(t.y()) << " " << FormatDouble(t.z()) << " " << image.camera_id << " "
        << image.name << "\n";
    std::string line;
    for (const Point2D& point2D : image.points2D) {
      line += FormatDouble(point2D.xy.x()) + " " + FormatDouble(point2D.xy.y()) + " " +
              (point2D.point3D_id == kInvalidPoint3DId ? std::string("-1")
                                                       : std::to_string(point2D.point3D_id)) +
              " ";
    }
    if (!line.empty()) line.pop_back();
    out << line << "\n";
  }
}

void WritePoints3DText(const Reconstruction& model, std::ostream& out) {
  const double mean_track_length =
      model.points3D.empty() ? 0.0
                             : static_cast<double>(NumObservations(model)) / model.points3D.size();
  out << "# 3D point list with one line of data per point:\n"
         "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n"
         "# Number of points: "
      << model.points3D.size() << ", mean track length: " << FormatDouble(mean_track_length)
      << "\n";
  for (const auto& [point3D_id, point] : model.points3D) {
    out << point3D_id << " " << FormatDouble(point.xyz.x()) << " " << FormatDouble(point.xyz.y())
        << " " << FormatDouble(point.xyz.z()) << " " << static_cast<int>(point.color[0]) << " "
        << static_cast<int>(point.color[1]) << " " << static_cast<int>(point.color[2]) << " "
        << FormatDouble(point.error);
    for (const TrackElement& element : point.track) {
      out << " " << element.image_id << " " << element.point2D_idx;
    }
    out << "\n";
  }
}

void WriteCamerasBinary(const Reconstruction& model, std::ostream& stream) {
  BinaryWriter out(stream);
  out.WriteUint64(model.cameras.size());
  for (const auto& [camera_id, camera] : model.cameras) {
    out.WriteUint32(camera_id);
    out.WriteInt32(static_cast<int32_t>(camera.model));
    out.WriteUint64(camera.width);
    out.WriteUint64(camera.height);
    for (const double param : camera.params) out.WriteDouble(param);
  }
}

void WriteImagesBinary(const Reconstruction& model, std::ostream& stream) {
  BinaryWriter out(stream);
  out.WriteUint64(model.images.size());
  for (const auto& [image_id, image] : model.images) {
    const Eigen::Quaterniond& q = image.cam_from_world.rotation;
    out.WriteUint32(image_id);
    out.WriteDouble(q.w());
    out.WriteDouble(q.x());
    out.WriteDouble(q.y());
    out.WriteDouble(q.z());
    for (int k = 0; k < 3; ++k) out.WriteDouble(image.cam_from_world.translation[k]);
    out.WriteUint32(image.camera_id);
    out.WriteString(image.name);
    out.WriteUint64(image.points2D.size());
    for (const Point2D& point2D : image.points2D) {
      out.WriteDouble(point2D.xy.x());
      out.WriteDouble(point2D.xy.y());
      out.WriteUint64(point2D.point3D_id);
    }
  }
}

void WritePoints3DBinary(const Reconstruction& model, std::ostream& stream) {
  BinaryWriter out(stream);
  out.WriteUint64(model.points3D.size());
  for (const auto& [point3D_id, point] : model.points3D) {
    out.WriteUint64(point3D_id);
    for (int k = 0; k < 3; ++k) out.WriteDouble(point.xyz[k]);
    for (int k = 0; k < 3; ++k) out.WriteUint8(point.color[k]);
    out.WriteDouble(point.error);
    out.WriteUint64(point.track.size());
    for (const TrackElement& element : point.track) {
      out.WriteUint32(element.image_id);
      out.WriteUint32(element.point2D_idx);
    }
  }
}

// Image names that the chosen format cannot carry back unchanged.
void CheckNamesWritable(const Reconstruction& model, const ModelFiles& files, ModelFormat format) {
  for (const auto& [image_id, image] : model.images) {
    const std::string problem = ImageNameProblem(image.name, format);
    if (!problem.empty()) throw InputError(files.images, ImageLabel(image) + ": " + problem);
  }
}

}  // namespace

ModelFormat ModelFormatFromName(const std::string& name, const std::string& option) {
  std::string upper = name;
  std::transform(upper.begin(), upper.end(), upper.begin(),
                 [](unsigned char c) { return std::toupper(c); });
  if (upper == "BIN") return ModelFormat::kBinary;
  if (upper == "TXT") return ModelFormat::kText;
  throw InputError(option, "'" + name + "' is not BIN or TXT");
}

std::string ImageNameProblem(const std::string& name, ModelFormat format) {
  if (name.empty()) return "has no name";
  if (name.find('\0') != std::string::npos) return "the name contains a NUL character";
  if (format == ModelFormat::kText && name.find_first_of(" \t\r\n\v\f") != std::string::npos) {
    return "COLMAP's text format cannot hold a name with white space; write the binary format";
  }
  return "";
}

void CheckImageNamesFit(const FeatureDatabase& database, ModelFormat format,
                        const std::string& source, const std::string& why_format) {
  for (const auto& [image_id, image] : database.images) {
    const std::string problem = ImageNameProblem(image.name, format);
    if (!problem.empty()) {
      throw InputError(source, "image " + std::to_string(image_id) + " '" + image.name +
                                   "': " + problem + " (" + why_format + ")");
    }
  }
}

Reconstruction ReadColmapModel(const std::string& path) {
  std::error_code ec;
  if (!fs::is_directory(path, ec)) throw InputError(path, "model folder not found");
  if (fs::exists(fs::path(path) / "cameras.bin", ec)) return ReadColmapModelBinary(path);
  if (fs::exists(fs::path(path) / "cameras.txt", ec)) return ReadColmapModelText(path);
  throw InputError(path, "no COLMAP model here (neither cameras.bin nor cameras.txt)");
}

Reconstruction ReadColmapModelBinary(const std::string& path) {
  const ModelFiles files = FilesIn(path, ".bin");
  Reconstruction model;
  ReadCamerasBinary(files.cameras, &model);
  ReadImagesBinary(files.images, &model);
  ReadPoints3DBinary(files.points3D, &model);
  CheckModel(model, files);
  ReadColmapModelRigs(path, /*binary=*/true, &model);
  return model;
}

Reconstruction ReadColmapModelText(const std::string& path) {
  const ModelFiles files = FilesIn(path, ".txt");
  Reconstruction model;
  ReadCamerasText(files.cameras, &model);
  ReadImagesText(files.images, &model);
  ReadPoints3DText(files.points3D, &model);
  CheckModel(model, files);
  ReadColmapModelRigs(path, /*binary=*/false, &model);
  return model;
}

namespace {

// Refuses a folder that cannot take the model: a file in its place, a model of the other format
// in it, or a folder where a model file goes.
void CheckModelFolder(const std::string& path, bool binary, const ModelFiles& final_files) {
  std::error_code ec;
  if (fs::exists(path, ec) && !fs::is_directory(path, ec)) {
    throw InputError(path, "exists and is not a folder");
  }
  if (!fs::is_directory(path, ec)) return;
  // A model of the other format beside the new one would be what readers see (COLMAP reads .bin
  // first), so a mixed folder is refused rather than silently shadowed or cleaned up.
  const ModelFiles other = FilesIn(path, binary ? ".txt" : ".bin");
  for (const std::string& file : {other.cameras, other.images, other.points3D}) {
    if (fs::exists(file, ec)) {
      throw InputError(path, "already holds a " + std::string(binary ? "text" : "binary") +
                                 " model (" + file + "); write the " +
                                 (binary ? "binary" : "text") +
                                 " model to another folder, or remove that one first");
    }
  }
  for (const std::string& file : {final_files.cameras, final_files.images, final_files.points3D}) {
    if (fs::is_directory(file, ec)) throw InputError(file, "is a folder; expected a model file");
  }
}

// A new folder staged whole (null when `path` exists: its files are staged one by one).
std::unique_ptr<StagedPath> StagedModelFolder(const std::string& path) {
  std::error_code ec;
  if (fs::exists(path, ec)) return nullptr;
  fs::path folder_path = fs::absolute(fs::path(path));
  if (!folder_path.has_filename()) folder_path = folder_path.parent_path();  // "out/"
  fs::create_directories(folder_path.parent_path(), ec);
  if (ec) throw InputError(path, "cannot create the parent folder: " + ec.message());
  auto staged = std::make_unique<StagedPath>(path);
  fs::create_directory(staged->path(), ec);
  if (ec) throw InputError(path, "cannot create the folder: " + ec.message());
  return staged;
}

// One file of a model: where it ends up, where it is written first, and what writes it.
struct ModelPart {
  std::string final_path;
  std::string path;
  std::function<void(std::ostream&)> write;
};

// The five files: COLMAP 3.8's three, and COLMAP 4's rigs and frames (3.8 ignores them).
std::vector<ModelPart> ModelParts(const Reconstruction& reconstruction,
                                  const ModelRigsAndFrames& rigs, const std::string& path,
                                  const std::string& folder, bool binary) {
  const std::string extension = binary ? ".bin" : ".txt";
  const auto part = [&](const std::string& name, std::function<void(std::ostream&)> write) {
    return ModelPart{(fs::path(path) / (name + extension)).string(),
                     (fs::path(folder) / (name + extension)).string(), std::move(write)};
  };
  const auto model = [&](void (*write)(const Reconstruction&, std::ostream&)) {
    return [&reconstruction, write](std::ostream& out) { write(reconstruction, out); };
  };
  const auto rig = [&](void (*write)(const ModelRigsAndFrames&, std::ostream&)) {
    return [&rigs, write](std::ostream& out) { write(rigs, out); };
  };
  return {
      part("cameras", model(binary ? &WriteCamerasBinary : &WriteCamerasText)),
      part("images", model(binary ? &WriteImagesBinary : &WriteImagesText)),
      part("points3D", model(binary ? &WritePoints3DBinary : &WritePoints3DText)),
      part("rigs", rig(binary ? &WriteRigsBinary : &WriteRigsText)),
      part("frames", rig(binary ? &WriteFramesBinary : &WriteFramesText)),
  };
}

}  // namespace

void WriteColmapModel(const Reconstruction& reconstruction, const std::string& path,
                      ModelFormat format) {
  const bool binary = format == ModelFormat::kBinary;
  const ModelFiles final_files = FilesIn(path, binary ? ".bin" : ".txt");
  // Everything is checked before anything is created, so a bad model leaves no trace.
  CheckModel(reconstruction, final_files);
  CheckNamesWritable(reconstruction, final_files, format);
  CheckModelFolder(path, binary, final_files);
  const ModelRigsAndFrames rigs = RigsAndFramesToWrite(reconstruction);

  // A new folder is staged whole; into an existing one, the files are staged side by side and
  // renamed only once all of them are complete.
  const std::unique_ptr<StagedPath> staged_folder = StagedModelFolder(path);
  const std::string folder = staged_folder ? staged_folder->path() : path;
  std::vector<std::unique_ptr<StagedPath>> staged_files;
  for (const ModelPart& part : ModelParts(reconstruction, rigs, path, folder, binary)) {
    std::string target = part.path;
    if (!staged_folder) {
      staged_files.push_back(std::make_unique<StagedPath>(part.path));
      target = staged_files.back()->path();
    }
    std::ofstream file(target, binary ? std::ios::binary | std::ios::out : std::ios::out);
    if (!file) throw InputError(part.final_path, "cannot open for writing");
    part.write(file);
    file.flush();
    if (!file) throw InputError(part.final_path, "write failed (disk full?)");
  }
  if (staged_folder) {
    staged_folder->Commit();
  } else {
    for (const auto& staged : staged_files) staged->Commit();
  }
}

}  // namespace ramap
