#pragma once
// The curvature estimate curvature() runs and measure(), features() and lines() run when given no
// curvature arrays: its arguments (estimator=, scale=, normals=, ao_scale=, ao_method=,
// hattori_half=, iso=), the CLI's rules
// on them, and the report it returns.
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "curvature/curvature_field.h"
#include "curvature/estimator.h"
#include "curvature/request.h"
#include "python/detail/args.h"
#include "volume/gradient_normals.h"

namespace isocurv::python {

/// The estimator called `name` (ValueError naming `arg` and listing the names otherwise).
curvature::Estimator estimator_of(const py::object& name, const char* arg);

/// scale= as the CLI's --scale: None or 'auto' (0: chosen from the data) or a positive number.
double scale_of(const py::object& scale);

/// normals= for the mesh estimators: None (automatic, the default), 'volume', 'mesh', 'area' or
/// 'face-average' (the CLI's --normals).
curvature::NormalsSource normals_of(const py::object& normals);

/// ao_method= as the CLI's --ao-method: None (griffin, the estimators' own) or one of
/// ao::method_names() (TypeError, or ValueError listing the names, otherwise).
ao::Method ao_method_of(const py::object& method);

/// A curvature request's error (curvature::resolve) in the module's words: a ValueError naming
/// the argument ("normals: applies to the mesh estimators; ...").
py::value_error request_error(const curvature::RequestError& e);

/// What a curvature call used, as CurvatureArrays.report: {"estimator", "parameters" {name:
/// value}, "chosen" {name: 'auto'|'given'}, "unreliable", "normals"[, "normal_fallbacks"]}.
py::dict report_dict(const curvature::EstimatorReport& r, const std::string& normals,
                     const volume::MeshNormals* vn);

/// A ValueError unless `mesh` lies in `volume`: its bounding box (finite vertices) within the
/// volume's world bounds (the domain's corners through the transform) grown by one voxel (the
/// longest voxel edge). A mesh of another volume, or of this one loaded with another spacing or
/// origin, would otherwise be measured in the volume's outside: wrong curvature, no error.
void check_mesh_in_volume(const Mesh& mesh, const volume::Volume& volume);

/// A curvature estimate and what it used (CurvatureArrays.report).
struct Estimated {
  curvature::CurvatureField field;
  py::dict report;
};

/// curvature()'s estimate (the CLI's rules: curvature::resolve), also what features() and lines() estimate when
/// given no curvature arrays.
Estimated estimate_of(const std::shared_ptr<PyMesh>& mesh, const volume::Volume* volume,
                      py::object estimator, py::object scale, py::object normals_arg,
                      py::object iso, py::object ao_scale, bool cap, py::object device,
                      py::object ao_method = py::none(), bool hattori_half = false);

/// The isovalue of `mesh` for the volume stages: iso= when given, else mesh.isovalue (set by
/// extract); a ValueError naming `why` when neither.
float mesh_isovalue(const PyMesh& mesh, const py::object& iso, const std::string& why);

/// The curvature field the features and lines read: `arrays` (a dict as curvature() returns)
/// checked to carry `needed`, or, for None, curvature(mesh, volume, iso=iso) with its defaults.
curvature::CurvatureField field_for(const std::shared_ptr<PyMesh>& mesh,
                                    const volume::Volume* volume, const py::object& arrays,
                                    const py::object& iso, py::object device,
                                    std::initializer_list<const char*> needed);

}  // namespace isocurv::python
