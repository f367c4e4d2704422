#include "ramap/io/g2o_reader.h"

#include <Eigen/Dense>
#include <cmath>
#include <fstream>
#include <sstream>
#include <unordered_set>

#include "ramap/util/error.h"

namespace ramap {
namespace {

// Reads `count` numbers or throws.
std::vector<double> ReadNumbers(std::istringstream& in, int count, const std::string& path,
                                int line_number, const std::string& tag) {
  std::vector<double> values(count);
  for (int k = 0; k < count; ++k) {
    if (!(in >> values[k])) {
      throw InputError(path, "line " + std::to_string(line_number) + ": " + tag + " expects " +
                                 std::to_string(count) + " numbers after the ids");
    }
  }
  return values;
}

uint32_t ReadId(std::istringstream& in, const std::string& path, int line_number,
                const std::string& tag) {
  long long id = -1;
  if (!(in >> id) || id < 0 || id > 0xffffffffLL) {
    throw InputError(path, "line " + std::to_string(line_number) + ": " + tag +
                               " needs non-negative integer ids");
  }
  return static_cast<uint32_t>(id);
}

Eigen::Quaterniond UnitQuaternion(double qx, double qy, double qz, double qw,
                                  const std::string& path, int line_number) {
  Eigen::Quaterniond q(qw, qx, qy, qz);
  const double norm = q.norm();
  if (!(norm > 0.5 && norm < 1.5)) {
    throw InputError(path,
                     "line " + std::to_string(line_number) + ": quaternion is not of unit norm");
  }
  return q.normalized();
}

}  // namespace

G2oPoseGraph ReadG2oPoseGraph(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw InputError(path, "cannot open the g2o file");
  G2oPoseGraph result;
  std::unordered_set<uint32_t> seen;
  auto add_node = [&](uint32_t id) {
    if (seen.insert(id).second) result.graph.node_ids.push_back(id);
  };
  std::string line;
  int line_number = 0;
  while (std::getline(file, line)) {
    ++line_number;
    std::istringstream in(line);
    std::string tag;
    if (!(in >> tag)) continue;
    if (tag == "VERTEX_SE3:QUAT") {
      const uint32_t id = ReadId(in, path, line_number, tag);
      const auto v = ReadNumbers(in, 7, path, line_number, tag);
      add_node(id);
      result.vertex_rotations[id] =
          UnitQuaternion(v[3], v[4], v[5], v[6], path, line_number).conjugate();
    } else if (tag == "VERTEX_SE2") {
      const uint32_t id = ReadId(in, path, line_number, tag);
      const auto v = ReadNumbers(in, 3, path, line_number, tag);
      add_node(id);
      result.vertex_rotations[id] =
          Eigen::Quaterniond(Eigen::AngleAxisd(-v[2], Eigen::Vector3d::UnitZ()));
      result.planar = true;
    } else if (tag == "EDGE_SE3:QUAT" || tag == "EDGE_SE2") {
      const bool planar = tag == "EDGE_SE2";
      RelativeRotationEdge edge;
      edge.i = ReadId(in, path, line_number, tag);
      edge.j = ReadId(in, path, line_number, tag);
      if (edge.i == edge.j) {
        throw InputError(path, "line " + std::to_string(line_number) + ": edge is a self loop");
      }
      if (planar) {
        const auto v = ReadNumbers(in, 3 + 6, path, line_number, tag);
        edge.R_ij = Eigen::Quaterniond(Eigen::AngleAxisd(-v[2], Eigen::Vector3d::UnitZ()));
        edge.weight = v[8];  // I33, the theta information
        result.planar = true;
      } else {
        const auto v = ReadNumbers(in, 7 + 21, path, line_number, tag);
        edge.R_ij = UnitQuaternion(v[3], v[4], v[5], v[6], path, line_number).conjugate();
        // Upper triangle row by row of the 6x6 information, order (x, y, z, rx, ry, rz).
        Eigen::Matrix<double, 6, 6> information;
        int k = 7;
        for (int r = 0; r < 6; ++r) {
          for (int c = r; c < 6; ++c) {
            information(r, c) = information(c, r) = v[k++];
          }
        }
        const Eigen::Matrix3d rotation_information = information.bottomRightCorner<3, 3>();
        const double trace = rotation_information.inverse().trace();
        edge.weight = std::isfinite(trace) && trace > 0 ? 3.0 / (2.0 * trace) : 1.0;
      }
      if (!(edge.weight > 0.0)) edge.weight = 1.0;
      add_node(edge.i);
      add_node(edge.j);
      result.graph.edges.push_back(edge);
    }
  }
  if (file.bad()) throw InputError(path, "read error");
  return result;
}

}  // namespace ramap
