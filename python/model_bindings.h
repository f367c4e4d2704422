// ramap.Reconstruction, Camera, Image, Point3D and Rigid3d for Python.
#pragma once

#include <pybind11/pybind11.h>

namespace ramap::python {

void BindModel(pybind11::module_& m);

}  // namespace ramap::python
