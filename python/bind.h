#pragma once
// The areas of the isocurv Python module: each bind_<area>(m) defines that area's classes and
// functions, with their docstrings, in python/<area>.cpp; python/module.cpp calls them in turn.
#include <pybind11/pybind11.h>

namespace isocurv::python {

void bind_volume(pybind11::module_& m);     ///< Volume, load, from_array (volume.cpp)
void bind_mesh(pybind11::module_& m);       ///< Mesh, extract, read_mesh, write_mesh, check (mesh.cpp)
void bind_curvature(pybind11::module_& m);  ///< curvature, estimator_names, Topology (curvature.cpp)
void bind_measure(pybind11::module_& m);    ///< measure, measure_labels (measure.cpp)
void bind_labels(pybind11::module_& m);     ///< extract_labels, curvature_labels (labels.cpp)
void bind_features(pybind11::module_& m);   ///< features (features.cpp)
void bind_lines(pybind11::module_& m);      ///< lines (lines.cpp)
void bind_screen(pybind11::module_& m);     ///< screen (screen.cpp)

}  // namespace isocurv::python
