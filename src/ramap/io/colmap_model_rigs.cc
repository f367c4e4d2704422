#include "ramap/io/colmap_model_rigs.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

#include "ramap/io/model_file_io.h"
#include "ramap/util/error.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

bool RigHasSensor(const Rig& rig, const SensorId& sensor) {
  return rig.ref_sensor == sensor ||
         std::any_of(rig.sensors.begin(), rig.sensors.end(),
                     [&](const RigSensor& other) { return other.sensor == sensor; });
}

// Checks shared by both formats, once both files are read.
void CheckRigsAndFrames(const Reconstruction& model, const std::string& rigs_path,
                        const std::string& frames_path) {
  const auto check_camera = [&](const SensorId& sensor, const std::string& what) {
    if (sensor.type == SensorType::kCamera && model.cameras.count(sensor.id) == 0) {
      throw InputError(rigs_path, what + ": " + SensorLabel(sensor) + " is not in the model");
    }
  };
  for (const auto& [rig_id, rig] : model.rigs) {
    const std::string what = "rig " + std::to_string(rig_id);
    check_camera(rig.ref_sensor, what);
    for (const RigSensor& sensor : rig.sensors) check_camera(sensor.sensor, what);
  }
  for (const auto& [frame_id, frame] : model.frames) {
    const std::string what = "frame " + std::to_string(frame_id);
    const auto rig = model.rigs.find(frame.rig_id);
    if (rig == model.rigs.end()) {
      throw InputError(frames_path,
                       what + ": rig " + std::to_string(frame.rig_id) + " is not in " + rigs_path);
    }
    for (const FrameData& data : frame.data) {
      if (!RigHasSensor(rig->second, data.sensor)) {
        throw InputError(frames_path, what + ": " + SensorLabel(data.sensor) +
                                          " is not a sensor of rig " +
                                          std::to_string(frame.rig_id));
      }
      if (data.sensor.type != SensorType::kCamera) continue;
      const auto image = model.images.find(static_cast<uint32_t>(data.data_id));
      if (image == model.images.end() || image->second.camera_id != data.sensor.id) {
        throw InputError(frames_path, what + ": image " + std::to_string(data.data_id) + " of " +
                                          SensorLabel(data.sensor) + " is not in the model");
      }
    }
  }
}

SensorId ReadSensorBinary(BinaryReader& in, const std::string& what) {
  const int32_t type = in.ReadInt32();
  const std::optional<SensorType> sensor_type = SensorTypeFromId(type);
  if (!sensor_type) {
    throw InputError(in.path(), what + ": unknown sensor type " + std::to_string(type));
  }
  return SensorId{*sensor_type, in.ReadUint32()};
}

Rigid3d ReadPoseBinary(BinaryReader& in) {
  double v[7];
  for (double& value : v) value = in.ReadDouble();
  return Rigid3d(Eigen::Quaterniond(v[0], v[1], v[2], v[3]), Eigen::Vector3d(v[4], v[5], v[6]));
}

void ReadRigsBinary(const std::string& path, Reconstruction* model) {
  BinaryReader in(path);
  in.SetItem("the number of rigs");
  const uint64_t count = in.ReadUint64();
  for (uint64_t i = 0; i < count; ++i) {
    const std::string item = "rig " + Ordinal(i, count);
    in.SetItem(item);
    Rig rig;
    rig.rig_id = in.ReadUint32();
    const uint32_t num_sensors = in.ReadUint32();
    if (num_sensors == 0) throw InputError(path, item + ": a rig without sensors");
    rig.ref_sensor = ReadSensorBinary(in, item);
    for (uint32_t k = 1; k < num_sensors; ++k) {
      RigSensor sensor;
      sensor.sensor = ReadSensorBinary(in, item);
      if (in.ReadUint8() != 0) sensor.sensor_from_rig = ReadPoseBinary(in);
      rig.sensors.push_back(sensor);
    }
    if (!model->rigs.emplace(rig.rig_id, rig).second) {
      throw InputError(path, item + ": duplicate rig id " + std::to_string(rig.rig_id));
    }
  }
  in.ExpectEnd();
}

void ReadFramesBinary(const std::string& path, Reconstruction* model) {
  BinaryReader in(path);
  in.SetItem("the number of frames");
  const uint64_t count = in.ReadUint64();
  for (uint64_t i = 0; i < count; ++i) {
    const std::string item = "frame " + Ordinal(i, count);
    in.SetItem(item);
    Frame frame;
    frame.frame_id = in.ReadUint32();
    frame.rig_id = in.ReadUint32();
    frame.rig_from_world = ReadPoseBinary(in);
    const uint32_t num_data = in.ReadUint32();
    in.ExpectRecords(num_data, 16);
    for (uint32_t k = 0; k < num_data; ++k) {
      FrameData data;
      data.sensor = ReadSensorBinary(in, item);
      data.data_id = in.ReadUint64();
      frame.data.push_back(data);
    }
    if (!model->frames.emplace(frame.frame_id, frame).second) {
      throw InputError(path, item + ": duplicate frame id " + std::to_string(frame.frame_id));
    }
  }
  in.ExpectEnd();
}

SensorId ReadSensorText(const TextLines& in, const std::string& type, const std::string& id,
                        const std::string& what) {
  const std::optional<SensorType> sensor_type = SensorTypeFromName(type);
  if (!sensor_type) in.Fail(what + ": unknown sensor type '" + type + "'");
  return SensorId{*sensor_type,
                  static_cast<uint32_t>(in.Unsigned(id, "the sensor id of " + what, kMaxUint32))};
}

Rigid3d ReadPoseText(const TextLines& in, const std::vector<std::string>& t, size_t first,
                     const std::string& what) {
  double v[7];
  for (int k = 0; k < 7; ++k) v[k] = in.FiniteDouble(t[first + k], "the pose of " + what);
  return Rigid3d(Eigen::Quaterniond(v[0], v[1], v[2], v[3]), Eigen::Vector3d(v[4], v[5], v[6]));
}

// RIG_ID NUM_SENSORS REF_TYPE REF_ID then (TYPE ID HAS_POSE [QW QX QY QZ TX TY TZ]) per sensor.
void ReadRigsText(const std::string& path, Reconstruction* model) {
  TextLines in(path);
  std::vector<std::string> t;
  while (in.NextDataLine(&t)) {
    if (t.size() < 4) in.Fail("expected RIG_ID NUM_SENSORS REF_SENSOR_TYPE REF_SENSOR_ID ...");
    Rig rig;
    rig.rig_id = static_cast<uint32_t>(in.Unsigned(t[0], "the rig id", kMaxUint32));
    const std::string what = "rig " + t[0];
    const uint64_t num_sensors = in.Unsigned(t[1], "the number of sensors of " + what, 1 << 20);
    if (num_sensors == 0) in.Fail(what + ": a rig without sensors");
    rig.ref_sensor = ReadSensorText(in, t[2], t[3], what);
    size_t next = 4;
    for (uint64_t k = 1; k < num_sensors; ++k) {
      if (next + 3 > t.size()) in.Fail(what + ": fewer sensors than its count");
      RigSensor sensor;
      sensor.sensor = ReadSensorText(in, t[next], t[next + 1], what);
      const bool has_pose = in.Unsigned(t[next + 2], "HAS_POSE of " + what, 1) == 1;
      next += 3;
      if (has_pose) {
        if (next + 7 > t.size()) in.Fail(what + ": a sensor pose with fewer than 7 values");
        sensor.sensor_from_rig = ReadPoseText(in, t, next, what);
        next += 7;
      }
      rig.sensors.push_back(sensor);
    }
    if (next != t.size()) in.Fail(what + ": more fields than its sensors take");
    if (!model->rigs.emplace(rig.rig_id, rig).second) in.Fail("duplicate rig id " + t[0]);
  }
}

// FRAME_ID RIG_ID QW QX QY QZ TX TY TZ NUM_DATA then (SENSOR_TYPE SENSOR_ID DATA_ID) per datum.
void ReadFramesText(const std::string& path, Reconstruction* model) {
  TextLines in(path);
  std::vector<std::string> t;
  while (in.NextDataLine(&t)) {
    if (t.size() < 10) in.Fail("expected FRAME_ID RIG_ID QW QX QY QZ TX TY TZ NUM_DATA_IDS ...");
    Frame frame;
    frame.frame_id = static_cast<uint32_t>(in.Unsigned(t[0], "the frame id", kMaxUint32));
    const std::string what = "frame " + t[0];
    frame.rig_id = static_cast<uint32_t>(in.Unsigned(t[1], "the rig of " + what, kMaxUint32));
    frame.rig_from_world = ReadPoseText(in, t, 2, what);
    const uint64_t num_data = in.Unsigned(t[9], "the number of data of " + what, 1 << 20);
    if (t.size() != 10 + 3 * num_data) in.Fail(what + ": its data are not NUM_DATA_IDS triples");
    for (uint64_t k = 0; k < num_data; ++k) {
      FrameData data;
      data.sensor = ReadSensorText(in, t[10 + 3 * k], t[11 + 3 * k], what);
      data.data_id = in.Unsigned(t[12 + 3 * k], "a data id of " + what, kMaxUint64);
      frame.data.push_back(data);
    }
    if (!model->frames.emplace(frame.frame_id, frame).second) in.Fail("duplicate frame id " + t[0]);
  }
}

bool SamePose(const Rigid3d& a, const Rigid3d& b) {
  const double angle = a.rotation.angularDistance(b.rotation);
  const double scale = std::max(1.0, std::max(a.translation.norm(), b.translation.norm()));
  return angle < 1e-6 && (a.translation - b.translation).norm() < 1e-6 * scale;
}

ModelRigsAndFrames OneRigPerCamera(const Reconstruction& model) {
  ModelRigsAndFrames out;
  for (const auto& [camera_id, camera] : model.cameras) {
    out.rigs.emplace(camera_id, OneCameraRig(camera_id));
  }
  for (const auto& [image_id, image] : model.images) {
    Frame frame = OneImageFrame(image_id, image.camera_id);
    frame.rig_from_world = image.cam_from_world;
    out.frames.emplace(image_id, frame);
  }
  return out;
}

// The registered image of `sensor` in `frame`, or null.
const Image* FrameImage(const Reconstruction& model, const Frame& frame, const SensorId& sensor) {
  if (sensor.type != SensorType::kCamera) return nullptr;
  for (const FrameData& data : frame.data) {
    if (!(data.sensor == sensor)) continue;
    const auto image = model.images.find(static_cast<uint32_t>(data.data_id));
    return image == model.images.end() ? nullptr : &image->second;
  }
  return nullptr;
}

// Each non-reference camera's sensor_from_rig from the first frame that registered it beside the
// reference camera; unchanged where no frame did.
Rigs RigsFromImages(const Reconstruction& model) {
  Rigs rigs = model.rigs;
  for (auto& [rig_id, rig] : rigs) {
    for (RigSensor& sensor : rig.sensors) {
      for (const auto& [frame_id, frame] : model.frames) {
        if (frame.rig_id != rig_id) continue;
        const Image* ref = FrameImage(model, frame, rig.ref_sensor);
        const Image* other = FrameImage(model, frame, sensor.sensor);
        if (ref == nullptr || other == nullptr) continue;
        sensor.sensor_from_rig = other->cam_from_world * ref->cam_from_world.Inverse();
        break;
      }
    }
  }
  return rigs;
}

// The frame's pose from one of its registered images, and its registered data only; nullopt when
// no image gives the pose, or the images disagree with the rig (adjusted one by one).
std::optional<Frame> FrameFromImages(const Reconstruction& model, const Rig& rig,
                                     const Frame& frame) {
  Frame out = frame;
  out.data.clear();
  std::optional<Rigid3d> rig_from_world;
  std::vector<std::pair<const Image*, Rigid3d>> images;  // image, its sensor_from_rig
  for (const FrameData& data : frame.data) {
    if (data.sensor.type != SensorType::kCamera) {
      out.data.push_back(data);
      continue;
    }
    const Image* image = FrameImage(model, frame, data.sensor);
    if (image == nullptr) continue;
    out.data.push_back(data);
    std::optional<Rigid3d> sensor_from_rig;
    if (rig.ref_sensor == data.sensor) sensor_from_rig = Rigid3d();
    for (const RigSensor& sensor : rig.sensors) {
      if (sensor.sensor == data.sensor) sensor_from_rig = sensor.sensor_from_rig;
    }
    if (!sensor_from_rig) return std::nullopt;  // COLMAP 4 could not pose this image
    images.emplace_back(image, *sensor_from_rig);
    if (!rig_from_world) rig_from_world = sensor_from_rig->Inverse() * image->cam_from_world;
  }
  if (!rig_from_world) return std::nullopt;
  for (const auto& [image, sensor_from_rig] : images) {
    if (!SamePose(sensor_from_rig * *rig_from_world, image->cam_from_world)) return std::nullopt;
  }
  out.rig_from_world = *rig_from_world;
  return out;
}

void WriteSensorBinary(BinaryWriter& out, const SensorId& sensor) {
  out.WriteInt32(static_cast<int32_t>(sensor.type));
  out.WriteUint32(sensor.id);
}

void WritePoseBinary(BinaryWriter& out, const Rigid3d& pose) {
  for (const double v : {pose.rotation.w(), pose.rotation.x(), pose.rotation.y(), pose.rotation.z(),
                         pose.translation.x(), pose.translation.y(), pose.translation.z()}) {
    out.WriteDouble(v);
  }
}

std::string PoseText(const Rigid3d& pose) {
  std::string text;
  for (const double v : {pose.rotation.w(), pose.rotation.x(), pose.rotation.y(), pose.rotation.z(),
                         pose.translation.x(), pose.translation.y(), pose.translation.z()}) {
    text += " " + FormatDouble(v);
  }
  return text;
}

std::string SensorText(const SensorId& sensor) {
  return " " + SensorTypeName(sensor.type) + " " + std::to_string(sensor.id);
}

}  // namespace

void ReadColmapModelRigs(const std::string& folder, bool binary, Reconstruction* model) {
  const std::string extension = binary ? ".bin" : ".txt";
  const std::string rigs_path = (fs::path(folder) / ("rigs" + extension)).string();
  const std::string frames_path = (fs::path(folder) / ("frames" + extension)).string();
  std::error_code ec;
  const bool has_rigs = fs::exists(rigs_path, ec);
  const bool has_frames = fs::exists(frames_path, ec);
  if (!has_rigs && !has_frames) return;
  if (has_rigs != has_frames) {
    throw InputError(has_rigs ? frames_path : rigs_path,
                     "file not found, though " + (has_rigs ? rigs_path : frames_path) +
                         " is there (a COLMAP 4 model holds both)");
  }
  if (binary) {
    ReadRigsBinary(rigs_path, model);
    ReadFramesBinary(frames_path, model);
  } else {
    ReadRigsText(rigs_path, model);
    ReadFramesText(frames_path, model);
  }
  CheckRigsAndFrames(*model, rigs_path, frames_path);
}

ModelRigsAndFrames RigsAndFramesToWrite(const Reconstruction& model) {
  if (model.rigs.empty() || model.frames.empty()) return OneRigPerCamera(model);
  ModelRigsAndFrames out;
  out.rigs = RigsFromImages(model);
  size_t num_images = 0;
  for (const auto& [frame_id, frame] : model.frames) {
    const auto rig = out.rigs.find(frame.rig_id);
    if (rig == out.rigs.end()) return OneRigPerCamera(model);
    const std::optional<Frame> posed = FrameFromImages(model, rig->second, frame);
    if (!posed) return OneRigPerCamera(model);
    const size_t num_frame_images = std::count_if(
        posed->data.begin(), posed->data.end(),
        [](const FrameData& data) { return data.sensor.type == SensorType::kCamera; });
    if (num_frame_images == 0) continue;  // no image of this frame was registered
    num_images += num_frame_images;
    out.frames.emplace(frame_id, *posed);
  }
  // Every registered image must belong to a frame for COLMAP 4 to read the model.
  if (num_images != model.images.size()) return OneRigPerCamera(model);
  return out;
}

void WriteRigsBinary(const ModelRigsAndFrames& rigs, std::ostream& stream) {
  BinaryWriter out(stream);
  out.WriteUint64(rigs.rigs.size());
  for (const auto& [rig_id, rig] : rigs.rigs) {
    out.WriteUint32(rig_id);
    out.WriteUint32(static_cast<uint32_t>(rig.num_sensors()));
    WriteSensorBinary(out, rig.ref_sensor);
    for (const RigSensor& sensor : rig.sensors) {
      WriteSensorBinary(out, sensor.sensor);
      out.WriteUint8(sensor.sensor_from_rig ? 1 : 0);
      if (sensor.sensor_from_rig) WritePoseBinary(out, *sensor.sensor_from_rig);
    }
  }
}

void WriteFramesBinary(const ModelRigsAndFrames& rigs, std::ostream& stream) {
  BinaryWriter out(stream);
  out.WriteUint64(rigs.frames.size());
  for (const auto& [frame_id, frame] : rigs.frames) {
    out.WriteUint32(frame_id);
    out.WriteUint32(frame.rig_id);
    WritePoseBinary(out, frame.rig_from_world);
    out.WriteUint32(static_cast<uint32_t>(frame.data.size()));
    for (const FrameData& data : frame.data) {
      WriteSensorBinary(out, data.sensor);
      out.WriteUint64(data.data_id);
    }
  }
}

void WriteRigsText(const ModelRigsAndFrames& rigs, std::ostream& out) {
  out << "# Rig calib list with one line of data per calib:\n"
         "#   RIG_ID, NUM_SENSORS, REF_SENSOR_TYPE, REF_SENSOR_ID, SENSORS[] as (SENSOR_TYPE, "
         "SENSOR_ID, HAS_POSE, [QW, QX, QY, QZ, TX, TY, TZ])\n"
         "# Number of rigs: "
      << rigs.rigs.size() << "\n";
  for (const auto& [rig_id, rig] : rigs.rigs) {
    out << rig_id << " " << rig.num_sensors() << SensorText(rig.ref_sensor);
    for (const RigSensor& sensor : rig.sensors) {
      out << SensorText(sensor.sensor) << (sensor.sensor_from_rig ? " 1" : " 0");
      if (sensor.sensor_from_rig) out << PoseText(*sensor.sensor_from_rig);
    }
    out << "\n";
  }
}

void WriteFramesText(const ModelRigsAndFrames& rigs, std::ostream& out) {
  out << "# Frame list with one line of data per frame:\n"
         "#   FRAME_ID, RIG_ID, RIG_FROM_WORLD[QW, QX, QY, QZ, TX, TY, TZ], NUM_DATA_IDS, "
         "DATA_IDS[] as (SENSOR_TYPE, SENSOR_ID, DATA_ID)\n"
         "# Number of frames: "
      << rigs.frames.size() << "\n";
  for (const auto& [frame_id, frame] : rigs.frames) {
    out << frame_id << " " << frame.rig_id << PoseText(frame.rig_from_world) << " "
        << frame.data.size();
    for (const FrameData& data : frame.data) out << SensorText(data.sensor) << " " << data.data_id;
    out << "\n";
  }
}

}  // namespace ramap
