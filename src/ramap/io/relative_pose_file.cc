#include "ramap/io/relative_pose_file.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "ramap/util/error.h"
#include "ramap/util/staged_output.h"

namespace ramap {
namespace {

void WriteQuaternion(std::ostream& out, const Eigen::Quaterniond& q) {
  out << q.w() << " " << q.x() << " " << q.y() << " " << q.z();
}

// Names are blank-separated fields: a name with a blank could not be read back.
void CheckName(const std::string& name, const std::string& path) {
  if (name.empty() || name.find_first_of(" \t\r\n") != std::string::npos) {
    throw InputError(path, "image name '" + name + "' is empty or holds a blank");
  }
}

}  // namespace

void WriteRelativePoses(const std::vector<RelativePoseRecord>& records, const std::string& path) {
  for (const RelativePoseRecord& r : records) {
    CheckName(r.image_name1, path);
    CheckName(r.image_name2, path);
  }
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "# ramap relative poses: NAME1 NAME2 qw qx qy qz tx ty tz num_inliers flags\n"
        << "# (q, t) = cam2_from_cam1, x_cam = R x_world + t; flags: 1 = pure rotation\n"
        << std::setprecision(17);
    for (const RelativePoseRecord& r : records) {
      out << r.image_name1 << " " << r.image_name2 << " ";
      WriteQuaternion(out, r.rotation);
      out << " " << r.translation.x() << " " << r.translation.y() << " " << r.translation.z() << " "
          << r.num_inliers << " " << r.flags << "\n";
    }
  });
}

void WriteRotations(const std::vector<RotationRecord>& records, const std::string& path) {
  for (const RotationRecord& r : records) CheckName(r.image_name, path);
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "# ramap rotations: NAME qw qx qy qz (cam_from_world, as COLMAP's images.txt)\n"
        << std::setprecision(17);
    for (const RotationRecord& r : records) {
      out << r.image_name << " ";
      WriteQuaternion(out, r.cam_from_world);
      out << "\n";
    }
  });
}

std::vector<RelativePoseRecord> ReadRelativePoses(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open the relative pose file");
  std::vector<RelativePoseRecord> records;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const size_t begin = line.find_first_not_of(" \t\r");
    if (begin == std::string::npos || line[begin] == '#') continue;
    const std::string where = "line " + std::to_string(line_number);
    std::istringstream fields(line);
    std::vector<std::string> tokens;
    for (std::string token; fields >> token;) tokens.push_back(token);
    if (tokens.size() > 11) throw InputError(path, where + ": unexpected '" + tokens[11] + "'");
    // strtod, unlike a stream, reads "nan" and "inf", so that they are reported as such.
    std::vector<double> values;
    for (size_t k = 2; k < tokens.size(); ++k) {
      char* end = nullptr;
      values.push_back(std::strtod(tokens[k].c_str(), &end));
      if (*end != '\0') values.pop_back();
    }
    if (tokens.size() < 11 || values.size() != 9) {
      throw InputError(path,
                       where + ": expected NAME1 NAME2 qw qx qy qz tx ty tz num_inliers flags");
    }
    RelativePoseRecord r;
    r.image_name1 = tokens[0];
    r.image_name2 = tokens[1];
    const double qw = values[0], qx = values[1], qy = values[2], qz = values[3];
    r.translation = Eigen::Vector3d(values[4], values[5], values[6]);
    const double inliers = values[7], flags = values[8];
    r.rotation = Eigen::Quaterniond(qw, qx, qy, qz);
    if (!r.rotation.coeffs().allFinite() || !r.translation.allFinite()) {
      throw InputError(path, where + ": a value is not finite");
    }
    if (std::abs(r.rotation.norm() - 1.0) > 1e-3) {
      throw InputError(path, where + ": the quaternion is not of unit norm (|q| = " +
                                 std::to_string(r.rotation.norm()) + ")");
    }
    r.rotation.normalize();
    if (r.image_name1 == r.image_name2) {
      throw InputError(path, where + ": pairs an image (" + r.image_name1 + ") with itself");
    }
    if (inliers < 0 || flags < 0 || inliers != std::floor(inliers) || flags != std::floor(flags) ||
        inliers > 2e9 || flags > 4e9) {
      throw InputError(path, where + ": num_inliers and flags must be whole numbers >= 0");
    }
    r.num_inliers = static_cast<int>(inliers);
    r.flags = static_cast<uint32_t>(flags);
    records.push_back(std::move(r));
  }
  if (records.empty()) throw InputError(path, "holds no relative pose");
  return records;
}

}  // namespace ramap
