// The label-map area of the isocurv Python module: extract_labels and curvature_labels, the
// command line's extract --labels and curvature --labels (docs/labels.md): one surface per label,
// each at the half level of its own indicator, merged into one mesh with a per-vertex Label array.
// measure_labels (measure.cpp) measures the same surfaces.
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "curvature/curvature_field.h"
#include "labels/label_map.h"
#include "labels/label_merge.h"
#include "labels/label_surfaces.h"
#include "python/bind.h"
#include "python/detail/args.h"
#include "python/detail/arrays.h"
#include "python/detail/estimate.h"
#include "python/detail/labels.h"

namespace isocurv::python {

namespace {

/// The merged labels' surfaces as the module returns them: the Mesh (no isovalue: its surfaces lie
/// at 0.5 of each label's indicator, not at a level of the label map) and the merged field's
/// arrays (the per-vertex Label, and the curvature when estimated) as a dict, or a
/// CurvatureArrays carrying `report`.
py::tuple labelled_result(labels::LabelSurfaces&& made, const py::dict* report) {
  warn_filling_labels(made.empty);
  if (made.merged.parts.empty()) {
    std::string values;
    for (std::int64_t v : made.empty) values += (values.empty() ? "" : ", ") + std::to_string(v);
    throw py::value_error("labels: no label has a surface (" + values +
                          (made.empty.size() == 1 ? " fills" : " fill") + " the volume's box)");
  }
  auto mesh = std::make_shared<PyMesh>();
  mesh->mesh = std::move(made.merged.mesh);
  py::object arrays = report ? curvature_arrays(std::move(made.merged.field), *report)
                             : field_dict(std::move(made.merged.field));
  return py::make_tuple(mesh, arrays);
}

py::tuple extract_labels_of(const VolumeArg& volume_arg, const py::object& labels_arg,
                            py::object device) {
  const volume::Volume& v = volume_of(volume_arg, "volume");
  const DeviceChoice dc = device_choice(device);
  const std::vector<labels::Label> picked = picked_labels_of(v, labels_arg);
  labels::LabelSurfaceSteps steps;
  steps.margin = labels::scale_margin(v);  // as the command line without --scale
  steps.extract = label_extraction(dc);
  return labelled_result(labels::label_surfaces(v, picked, steps), nullptr);
}

/// The counts of a per-label report summed into `total` (a copy of the first label's report).
void add_label_counts(py::dict& total, const py::dict& part) {
  for (const char* key : {"unreliable", "implausible"})
    if (total.contains(key) && part.contains(key))
      total[key] = total[key].cast<std::int64_t>() + part[key].cast<std::int64_t>();
  if (total.contains("normal_fallbacks") && part.contains("normal_fallbacks")) {
    py::dict sum, a = total["normal_fallbacks"].cast<py::dict>(), b = part["normal_fallbacks"].cast<py::dict>();
    for (const auto& [key, value] : a) sum[key] = value.cast<std::int64_t>() + b[key].cast<std::int64_t>();
    total["normal_fallbacks"] = sum;
  }
}

py::tuple curvature_labels_of(const VolumeArg& volume_arg, const py::object& labels_arg,
                              py::object estimator, py::object scale, py::object normals,
                              py::object ao_scale, py::object device) {
  const volume::Volume& v = volume_of(volume_arg, "volume");
  const DeviceChoice dc = device_choice(device);
  const double sigma = scale_of(scale);  // TypeError / ValueError before any work
  const std::vector<labels::Label> picked = picked_labels_of(v, labels_arg);
  labels::LabelSurfaceSteps steps;
  steps.margin = labels::scale_margin(v, {sigma});  // as the command line's --scale
  steps.extract = label_extraction(dc);
  py::list reports, values;
  steps.curvature = [&](const Mesh& mesh, const volume::Volume& indicator, float isovalue) {
    auto m = std::make_shared<PyMesh>();
    m->mesh = mesh;
    m->isovalue = isovalue;  // the volume estimator's level in the indicator
    // curvature(m, indicator, ...): the CLI's rules on the arguments, its defaults (the volume
    // estimator, at the binary scale on an indicator).
    Estimated e = estimate_of(m, &indicator, estimator, scale, normals, py::none(), ao_scale,
                              false, device);
    reports.append(e.report);
    return std::move(e.field);
  };
  labels::LabelSurfaces made = labels::label_surfaces(v, picked, steps);
  py::dict report;
  if (!reports.empty()) {
    report = reports[0].attr("copy")();  // the per-label reports stay as made
    for (std::size_t k = 1; k < reports.size(); ++k) add_label_counts(report, reports[k].cast<py::dict>());
  }
  for (const labels::LabelPart& p : made.merged.parts) values.append(p.value);
  report["labels"] = values;
  report["label_reports"] = reports;
  return labelled_result(std::move(made), &report);
}

}  // namespace

void bind_labels(py::module_& m) {
  m.def("extract_labels", &extract_labels_of, py::arg("volume"), py::arg("labels") = py::none(),
        py::kw_only(), py::arg("device") = py::none(),
        R"doc(The surfaces of the labels of the label map `volume` (an integer segmentation; isocurv
extract --labels, see docs/labels.md) as one mesh: each label's marching-cubes surface at the half
level of its own indicator (1 on the label's voxels, 0 elsewhere), so touching labels each get a
closed surface, one after another in ascending label order (or `labels`' order). Returns
(mesh, arrays) as read_mesh does for the command line's file: `arrays` holds 'Label', each
vertex's label as float32 (as the files carry it); a triangle's label is
arrays['Label'][mesh.triangles[:, 0]] (labels never share a vertex). mesh.isovalue is None: the
surfaces lie at 0.5 of each label's indicator, not at a level of `volume` (curvature_labels
estimates on those). The same vertices, triangles and arrays as the command line's.
labels: None (all), an int or a sequence of ints (Python or numpy integers within +-16,777,215);
labels the volume lacks, and labels that fill the volume's box (no surface), are left out with a
UserWarning; none of `labels` in the volume, or none with a surface, raises ValueError. A float
volume, or more than 65,535 labels, raises isocurv.Error. device: as extract().)doc");

  m.def("curvature_labels", &curvature_labels_of, py::arg("volume"),
        py::arg("labels") = py::none(), py::kw_only(), py::arg("estimator") = py::none(),
        py::arg("scale") = py::none(), py::arg("normals") = py::none(),
        py::arg("ao_scale") = py::none(), py::arg("device") = py::none(),
        R"doc(The surfaces of the labels of the label map `volume` with their curvature (isocurv
curvature --labels, see docs/labels.md): extract_labels(volume, labels), each label's curvature
estimated on its own indicator, never across a label boundary (by default the volume estimator,
at the binary scale of 2 voxels). Returns (mesh, arrays): `arrays` is a CurvatureArrays holding
what curvature() gives, for all the labels one after another, and 'Label'; the same vertices,
triangles and arrays as the command line's file. arrays.report is the first label's report
(curvature()'s) with 'unreliable', 'implausible' and 'normal_fallbacks' summed over the labels,
'labels' (the values made, in order) and 'label_reports' (each label's own report).
estimator, scale, normals, ao_scale: as curvature() takes them, for each label's indicator; a
scale in world units also widens each label's cut-out (4 sigmas beyond the label). labels and
device, and what raises: as extract_labels.)doc");
}

}  // namespace isocurv::python
