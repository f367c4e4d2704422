#include "ramap/io/model_export.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <vector>

#include "ramap/io/trajectory.h"
#include "ramap/util/error.h"
#include "ramap/util/staged_output.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

// nerfstudio's world: COLMAP's axes turned so that z is up for its viewer (rows x, z, -y).
Eigen::Matrix4d NerfstudioWorldFromColmapWorld() {
  Eigen::Matrix4d turn = Eigen::Matrix4d::Zero();
  turn(0, 0) = 1;
  turn(1, 2) = 1;
  turn(2, 1) = -1;
  turn(3, 3) = 1;
  return turn;
}

void CheckHasImages(const Reconstruction& model, const std::string& source) {
  if (model.images.empty()) throw InputError(source, "the model has no image: nothing to export");
}

void CheckFinitePoses(const Reconstruction& model, const std::string& source) {
  for (const auto& [image_id, image] : model.images) {
    if (!image.cam_from_world.rotation.coeffs().allFinite() ||
        !image.cam_from_world.translation.allFinite() ||
        image.cam_from_world.rotation.norm() == 0.0) {
      throw InputError(source, "image " + std::to_string(image_id) + " ('" + image.name +
                                   "') has a NaN, infinite or zero pose");
    }
  }
}

void AppendFloat(std::string* out, float value) {
  char bytes[sizeof(float)];
  std::memcpy(bytes, &value, sizeof(float));  // PLY little endian: the machines ramap builds on
  out->append(bytes, sizeof(float));
}

struct PlyVertex {
  Eigen::Vector3d xyz;
  Eigen::Matrix<uint8_t, 3, 1> color;
};

void WritePly(const std::vector<PlyVertex>& vertices, const std::string& path) {
  std::string body;
  body.reserve(vertices.size() * 15);
  for (const PlyVertex& vertex : vertices) {
    for (int k = 0; k < 3; ++k) AppendFloat(&body, static_cast<float>(vertex.xyz[k]));
    body.append(reinterpret_cast<const char*>(vertex.color.data()), 3);
  }
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "ply\nformat binary_little_endian 1.0\ncomment written by ramap\nelement vertex "
        << vertices.size()
        << "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
           "property uchar green\nproperty uchar blue\nend_header\n";
    out.write(body.data(), static_cast<std::streamsize>(body.size()));
  });
}

std::vector<PlyVertex> PointVertices(const Reconstruction& model, const Eigen::Matrix4d& turn) {
  std::vector<PlyVertex> vertices;
  vertices.reserve(model.points3D.size());
  for (const auto& [point_id, point] : model.points3D) {
    if (!point.xyz.allFinite()) continue;
    vertices.push_back(
        {turn.topLeftCorner<3, 3>() * point.xyz + turn.topRightCorner<3, 1>(), point.color});
  }
  return vertices;
}

// nerfstudio's intrinsics fields for one COLMAP camera (its parse_colmap_camera_params).
nlohmann::json NerfstudioIntrinsics(const Camera& camera, const std::string& source) {
  const std::vector<double>& p = camera.params;
  nlohmann::json out = {{"w", camera.width}, {"h", camera.height}};
  const auto pinhole = [&](double fx, double fy, double cx, double cy) {
    out["fl_x"] = fx;
    out["fl_y"] = fy;
    out["cx"] = cx;
    out["cy"] = cy;
  };
  const auto distortion = [&](const char* model, std::vector<std::pair<const char*, double>> k) {
    for (const auto& [name, value] : k) out[name] = value;
    out["camera_model"] = model;
  };
  switch (camera.model) {
    case CameraModel::kSimplePinhole:
      pinhole(p[0], p[0], p[1], p[2]);
      distortion("OPENCV", {{"k1", 0.0}, {"k2", 0.0}, {"p1", 0.0}, {"p2", 0.0}});
      break;
    case CameraModel::kPinhole:
      pinhole(p[0], p[1], p[2], p[3]);
      distortion("OPENCV", {{"k1", 0.0}, {"k2", 0.0}, {"p1", 0.0}, {"p2", 0.0}});
      break;
    case CameraModel::kSimpleRadial:
      pinhole(p[0], p[0], p[1], p[2]);
      distortion("OPENCV", {{"k1", p[3]}, {"k2", 0.0}, {"p1", 0.0}, {"p2", 0.0}});
      break;
    case CameraModel::kRadial:
      pinhole(p[0], p[0], p[1], p[2]);
      distortion("OPENCV", {{"k1", p[3]}, {"k2", p[4]}, {"p1", 0.0}, {"p2", 0.0}});
      break;
    case CameraModel::kOpenCV:
      pinhole(p[0], p[1], p[2], p[3]);
      distortion("OPENCV", {{"k1", p[4]}, {"k2", p[5]}, {"p1", p[6]}, {"p2", p[7]}});
      break;
    case CameraModel::kOpenCVFisheye:
      pinhole(p[0], p[1], p[2], p[3]);
      distortion("OPENCV_FISHEYE", {{"k1", p[4]}, {"k2", p[5]}, {"k3", p[6]}, {"k4", p[7]}});
      break;
    case CameraModel::kSimpleRadialFisheye:
      pinhole(p[0], p[0], p[1], p[2]);
      distortion("OPENCV_FISHEYE", {{"k1", p[3]}, {"k2", 0.0}, {"k3", 0.0}, {"k4", 0.0}});
      break;
    case CameraModel::kRadialFisheye:
      pinhole(p[0], p[0], p[1], p[2]);
      distortion("OPENCV_FISHEYE", {{"k1", p[3]}, {"k2", p[4]}, {"k3", 0.0}, {"k4", 0.0}});
      break;
    default:
      throw InputError(source, "camera " + std::to_string(camera.camera_id) + " is " +
                                   CameraModelName(camera.model) +
                                   ", which nerfstudio's transforms.json cannot express; "
                                   "`ramap image_undistorter` makes a PINHOLE model of it");
  }
  return out;
}

// The frame's camera-to-world matrix as nerfstudio writes it: COLMAP's, its camera axes turned
// from OpenCV's (y down, z forward) to OpenGL's (y up, z backward), in the turned world.
Eigen::Matrix4d NerfstudioCameraToWorld(const Image& image) {
  const Rigid3d world_from_cam = image.cam_from_world.Inverse();
  Eigen::Matrix4d c2w = Eigen::Matrix4d::Identity();
  c2w.topLeftCorner<3, 3>() = world_from_cam.rotation.toRotationMatrix();
  c2w.topRightCorner<3, 1>() = world_from_cam.translation;
  c2w.block<3, 2>(0, 1) *= -1.0;
  return NerfstudioWorldFromColmapWorld() * c2w;
}

nlohmann::json MatrixRows(const Eigen::MatrixXd& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(m(r, c));
    rows.push_back(row);
  }
  return rows;
}

void CheckNotThere(const std::string& path) {
  std::error_code ec;
  if (fs::exists(fs::symlink_status(path, ec))) {
    throw InputError(path,
                     "already exists; ramap does not replace a file it may not have "
                     "written: remove it or export into another folder");
  }
}

}  // namespace

ExportFormat ExportFormatFromName(const std::string& name, const std::string& option) {
  std::string upper = name;
  std::transform(upper.begin(), upper.end(), upper.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  if (upper == "PLY") return ExportFormat::kPly;
  if (upper == "NERFSTUDIO") return ExportFormat::kNerfstudio;
  if (upper == "TUM") return ExportFormat::kTum;
  throw InputError(option, "'" + name + "' is not BIN, TXT, PLY, NERFSTUDIO or TUM");
}

void WritePointCloudPly(const Reconstruction& model, const std::string& path, bool with_cameras,
                        const std::string& source) {
  if (with_cameras) {
    CheckHasImages(model, source);
    CheckFinitePoses(model, source);
  }
  std::vector<PlyVertex> vertices = PointVertices(model, Eigen::Matrix4d::Identity());
  if (vertices.empty() && !with_cameras) {
    throw InputError(source,
                     "the model has no 3D point: nothing to export (add cameras with "
                     "--export_cameras 1)");
  }
  if (with_cameras) {
    for (const auto& [image_id, image] : model.images) {
      vertices.push_back({image.cam_from_world.Inverse().translation, {255, 0, 0}});
    }
  }
  WritePly(vertices, path);
}

void WriteTumExport(const Reconstruction& model, const std::string& path,
                    const std::string& source) {
  CheckHasImages(model, source);
  CheckFinitePoses(model, source);
  WriteTumTrajectory(model, path);
}

nlohmann::json NerfstudioTransforms(const Reconstruction& model, const std::string& source) {
  CheckHasImages(model, source);
  CheckFinitePoses(model, source);
  nlohmann::json out = nlohmann::json::object();
  const bool one_camera = model.cameras.size() == 1 && model.cameras.count(1) == 1;
  if (one_camera) out = NerfstudioIntrinsics(model.cameras.at(1), source);
  nlohmann::json frames = nlohmann::json::array();
  for (const auto& [image_id, image] : model.images) {
    nlohmann::json frame = {{"file_path", "images/" + image.name},
                            {"transform_matrix", MatrixRows(NerfstudioCameraToWorld(image))},
                            {"colmap_im_id", image_id}};
    if (!one_camera) {
      const auto camera = model.cameras.find(image.camera_id);
      if (camera == model.cameras.end()) {
        throw InputError(source, "image " + std::to_string(image_id) + " names camera " +
                                     std::to_string(image.camera_id) + ", which the model lacks");
      }
      frame.update(NerfstudioIntrinsics(camera->second, source));
    }
    frames.push_back(frame);
  }
  out["frames"] = frames;
  out["applied_transform"] = MatrixRows(NerfstudioWorldFromColmapWorld().topRows<3>());
  out["ply_file_path"] = "sparse_pc.ply";
  return out;
}

void WriteNerfstudioExport(const Reconstruction& model, const std::string& folder,
                           const std::string& source) {
  const nlohmann::json transforms = NerfstudioTransforms(model, source);
  const std::string transforms_path = folder + "/transforms.json";
  const std::string ply_path = folder + "/sparse_pc.ply";
  CheckNotThere(transforms_path);
  CheckNotThere(ply_path);
  CreatedOutput created(folder);
  fs::create_directories(folder);
  WritePly(PointVertices(model, NerfstudioWorldFromColmapWorld()), ply_path);
  try {
    WriteFileAtomically(transforms_path,
                        [&](std::ostream& out) { out << transforms.dump(4) << "\n"; });
  } catch (...) {
    std::error_code ec;
    fs::remove(ply_path, ec);  // the pair appears whole or not at all
    throw;
  }
  created.Keep();
}

}  // namespace ramap
