// ramap.Reconstruction and what it holds (cameras, images, points), shaped like pycolmap's
// classes. Every array handed to Python is a copy that Python owns, never a view into a model
// that may be freed.
#include "model_bindings.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <Eigen/Geometry>
#include <sstream>

#include "ramap/io/colmap_model.h"
#include "ramap/scene/reconstruction.h"

namespace py = pybind11;

namespace ramap::python {

namespace {

py::array_t<double> Vector(const double* data, size_t size) {
  py::array_t<double> out(size);
  std::copy(data, data + size, out.mutable_data());
  return out;
}

py::array_t<double> Matrix(const double* row_major, size_t rows, size_t cols) {
  py::array_t<double> out({rows, cols});
  std::copy(row_major, row_major + rows * cols, out.mutable_data());
  return out;
}

// A 3x4 [R | t] in row order.
py::array_t<double> PoseMatrix(const Rigid3d& pose) {
  const Eigen::Matrix<double, 3, 4, Eigen::RowMajor> m = pose.ToMatrix();
  return Matrix(m.data(), 3, 4);
}

void BindRigid(py::module_& m) {
  py::class_<Rigid3d>(m, "Rigid3d", "A rigid transform y = R x + t (cam_from_world for images)")
      .def_property_readonly(
          "rotation",
          [](const Rigid3d& pose) {
            const Eigen::Quaterniond& q = pose.rotation;
            const double xyzw[4] = {q.x(), q.y(), q.z(), q.w()};
            return Vector(xyzw, 4);
          },
          "the rotation as a unit quaternion, x y z w (pycolmap's order)")
      .def_property_readonly("translation",
                             [](const Rigid3d& pose) { return Vector(pose.translation.data(), 3); })
      .def("matrix", &PoseMatrix, "3x4 [R | t]")
      .def("inverse", &Rigid3d::Inverse)
      .def("__repr__", [](const Rigid3d& pose) {
        std::ostringstream out;
        out << "Rigid3d(quat_xyzw=[" << pose.rotation.x() << ", " << pose.rotation.y() << ", "
            << pose.rotation.z() << ", " << pose.rotation.w() << "], t=["
            << pose.translation.transpose() << "])";
        return out.str();
      });
}

void BindCamera(py::module_& m) {
  py::class_<Camera>(m, "Camera")
      .def_readonly("camera_id", &Camera::camera_id)
      .def_property_readonly("model", [](const Camera& c) { return CameraModelName(c.model); })
      .def_readonly("width", &Camera::width)
      .def_readonly("height", &Camera::height)
      .def_property_readonly(
          "params", [](const Camera& c) { return Vector(c.params.data(), c.params.size()); })
      .def_readonly("has_prior_focal_length", &Camera::has_prior_focal_length)
      .def("__repr__", [](const Camera& c) {
        std::ostringstream out;
        out << "Camera(camera_id=" << c.camera_id << ", model=" << CameraModelName(c.model)
            << ", width=" << c.width << ", height=" << c.height << ", params=[";
        for (size_t k = 0; k < c.params.size(); ++k) out << (k ? ", " : "") << c.params[k];
        out << "])";
        return out.str();
      });
}

void BindImage(py::module_& m) {
  py::class_<Image>(m, "Image")
      .def_readonly("image_id", &Image::image_id)
      .def_readonly("name", &Image::name)
      .def_readonly("camera_id", &Image::camera_id)
      .def_readonly("cam_from_world", &Image::cam_from_world)
      .def("projection_center",
           [](const Image& image) {
             const Eigen::Vector3d c = CameraCenter(image.cam_from_world);
             return Vector(c.data(), 3);
           })
      .def_property_readonly(
          "points2D",
          [](const Image& image) {
            py::array_t<double> xy({image.points2D.size(), size_t{2}});
            double* out = xy.mutable_data();
            for (const Point2D& p : image.points2D) {
              *out++ = p.xy.x();
              *out++ = p.xy.y();
            }
            return xy;
          },
          "keypoints, N x 2 pixels (0.5 is the first pixel's centre)")
      .def_property_readonly(
          "point3D_ids",
          [](const Image& image) {
            py::array_t<int64_t> ids(image.points2D.size());
            int64_t* out = ids.mutable_data();
            for (const Point2D& p : image.points2D) {
              *out++ = p.point3D_id == kInvalidPoint3DId ? -1 : static_cast<int64_t>(p.point3D_id);
            }
            return ids;
          },
          "the 3D point of each keypoint, -1 where none")
      .def("__repr__", [](const Image& image) {
        return "Image(image_id=" + std::to_string(image.image_id) + ", name='" + image.name +
               "', camera_id=" + std::to_string(image.camera_id) + ")";
      });
}

void BindPoint(py::module_& m) {
  py::class_<Point3D>(m, "Point3D")
      .def_property_readonly("xyz", [](const Point3D& p) { return Vector(p.xyz.data(), 3); })
      .def_property_readonly("color",
                             [](const Point3D& p) {
                               py::array_t<uint8_t> rgb(3);
                               std::copy(p.color.data(), p.color.data() + 3, rgb.mutable_data());
                               return rgb;
                             })
      .def_readonly("error", &Point3D::error)
      .def_property_readonly(
          "track",
          [](const Point3D& p) {
            py::array_t<int64_t> track({p.track.size(), size_t{2}});
            int64_t* out = track.mutable_data();
            for (const TrackElement& e : p.track) {
              *out++ = e.image_id;
              *out++ = e.point2D_idx;
            }
            return track;
          },
          "N x 2: image_id, point2D_idx");
}

template <typename Key, typename Value>
py::dict Copies(const std::map<Key, Value>& values) {
  py::dict out;
  for (const auto& [id, value] : values) out[py::int_(id)] = py::cast(value);
  return out;
}

// The dict of a model's cameras, images or points, made once per model object: the model cannot
// change from Python, and `model.images[k]` in a loop would otherwise copy every image each time.
template <typename Make>
py::object Cached(const py::object& self, const char* key, Make make) {
  py::dict attributes = self.attr("__dict__");
  if (!attributes.contains(key)) attributes[key] = make(self.cast<const Reconstruction&>());
  return attributes[key];
}

std::string Describe(const Reconstruction& model) {
  size_t num_observations = 0;
  for (const auto& [id, point] : model.points3D) num_observations += point.track.size();
  std::ostringstream out;
  out << "Reconstruction: " << model.cameras.size() << " cameras, " << model.images.size()
      << " registered images, " << model.points3D.size() << " points, " << num_observations
      << " observations";
  return out.str();
}

}  // namespace

void BindModel(py::module_& m) {
  BindRigid(m);
  BindCamera(m);
  BindImage(m);
  BindPoint(m);
  py::class_<Reconstruction>(m, "Reconstruction",
                             "A COLMAP model: cameras, registered images and 3D points",
                             py::dynamic_attr())
      .def(py::init<>())
      .def(py::init([](const std::string& path) {
             py::gil_scoped_release release;
             return ReadColmapModel(path);
           }),
           py::arg("path"), "reads a COLMAP model folder (.bin or .txt)")
      .def_property_readonly("cameras",
                             [](const py::object& self) {
                               return Cached(self, "_cameras", [](const Reconstruction& r) {
                                 return Copies(r.cameras);
                               });
                             })
      .def_property_readonly("images",
                             [](const py::object& self) {
                               return Cached(self, "_images", [](const Reconstruction& r) {
                                 return Copies(r.images);
                               });
                             })
      .def_property_readonly("points3D",
                             [](const py::object& self) {
                               return Cached(self, "_points3D", [](const Reconstruction& r) {
                                 return Copies(r.points3D);
                               });
                             })
      .def("num_cameras", [](const Reconstruction& r) { return r.cameras.size(); })
      .def("num_reg_images", [](const Reconstruction& r) { return r.images.size(); })
      .def("num_points3D", [](const Reconstruction& r) { return r.points3D.size(); })
      .def(
          "points3D_xyz",
          [](const Reconstruction& r) {
            py::array_t<double> xyz({r.points3D.size(), size_t{3}});
            double* out = xyz.mutable_data();
            for (const auto& [id, p] : r.points3D)
              out = std::copy(p.xyz.data(), p.xyz.data() + 3, out);
            return xyz;
          },
          "every point's position, N x 3, in id order")
      .def(
          "write",
          [](const Reconstruction& r, const std::string& path, bool binary) {
            py::gil_scoped_release release;
            WriteColmapModel(r, path, binary ? ModelFormat::kBinary : ModelFormat::kText);
          },
          py::arg("path"), py::arg("binary") = true,
          "writes cameras, images and points3D (.bin, or .txt with binary=False) into the folder")
      .def("summary", &Describe)
      .def("__repr__", &Describe);
}

}  // namespace ramap::python
