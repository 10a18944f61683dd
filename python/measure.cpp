// The measure area of the isocurv Python module: measure (per connected component) and
// measure_labels (per label of a label map).
#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "curvature/curvature_field.h"
#include "labels/label_map.h"
#include "labels/label_surfaces.h"
#include "measure/object_measures.h"
#include "python/bind.h"
#include "python/detail/args.h"
#include "python/detail/arrays.h"
#include "python/detail/estimate.h"
#include "python/detail/labels.h"

namespace isocurv::python {

namespace {

/// measure() and measure_labels()'s dict: one numpy array per measure, one entry per object.
struct MeasureColumns {
  std::vector<double> area, mesh_area, volume, int_h, int_k, gap, box, scale, curvature_genus;
  std::vector<std::int64_t> euler, genus, vertices, triangles, unmeasured;
  std::vector<std::uint8_t> closed, resolved, fine_handles;

  void add(const measure::ObjectMeasures& m) {
    area.push_back(m.area);
    mesh_area.push_back(m.mesh_area);
    scale.push_back(m.scale);
    resolved.push_back(m.resolved ? 1 : 0);
    volume.push_back(m.closed ? m.volume : std::numeric_limits<double>::quiet_NaN());
    int_h.push_back(m.integral_H);
    int_k.push_back(m.integral_K);
    gap.push_back(m.gauss_bonnet_gap());
    curvature_genus.push_back(m.curvature_genus());
    fine_handles.push_back(m.has_fine_handles() ? 1 : 0);
    euler.push_back(m.euler);
    genus.push_back(m.genus());
    vertices.push_back(std::int64_t(m.vertices));
    triangles.push_back(std::int64_t(m.triangles));
    unmeasured.push_back(std::int64_t(m.unmeasured));
    closed.push_back(m.closed ? 1 : 0);
    box.insert(box.end(), m.box.begin(), m.box.end());
  }
  py::dict dict() const {
    const py::ssize_t n = py::ssize_t(area.size());
    py::dict out;
    out["area"] = copy_array(area, {n});
    out["mesh_area"] = copy_array(mesh_area, {n});
    out["scale"] = copy_array(scale, {n});
    out["resolved"] = copy_array(resolved, {n});
    out["volume"] = copy_array(volume, {n});
    out["integral_H"] = copy_array(int_h, {n});
    out["integral_K"] = copy_array(int_k, {n});
    out["euler_characteristic"] = copy_array(euler, {n});
    out["genus"] = copy_array(genus, {n});
    out["gauss_bonnet_gap"] = copy_array(gap, {n});
    out["curvature_genus"] = copy_array(curvature_genus, {n});
    out["fine_handles"] = copy_array(fine_handles, {n});
    out["closed"] = copy_array(closed, {n});
    out["vertices"] = copy_array(vertices, {n});
    out["triangles"] = copy_array(triangles, {n});
    out["unmeasured_vertices"] = copy_array(unmeasured, {n});
    out["box"] = copy_array(box, {n, 6});
    return out;
  }
};

/// isocurv.measure: measure::object_measures as a dict of numpy arrays, one entry per component.
py::dict measure_of(const MeshArg& mesh_arg, const VolumeArg& volume_arg, const py::object& arrays,
                    const py::object& iso, py::object device) {
  const std::shared_ptr<PyMesh> mesh = mesh_of(mesh_arg, "mesh");
  const volume::Volume* volume = optional_volume(volume_arg, "volume");
  if (volume) check_mesh_in_volume(mesh->mesh, *volume);
  const curvature::CurvatureField field = field_for(mesh, volume, arrays, iso, device, {"H", "K"});
  MeasureColumns columns;
  for (const measure::ObjectMeasures& m : measure::object_measures(mesh->mesh, field)) columns.add(m);
  return columns.dict();
}

/// measure_labels(): the CLI's measure --labels, one entry per label.
py::dict measure_labels_of(const VolumeArg& volume_arg, const py::object& labels_arg, py::object device) {
  const volume::Volume& v = volume_of(volume_arg, "volume");
  const std::vector<labels::Label> picked = picked_labels_of(v, labels_arg);
  labels::LabelSurfaceSteps steps;
  steps.margin = labels::scale_margin(v);
  steps.extract = label_extraction(device_choice(device));
  std::vector<std::int64_t> label, components;
  MeasureColumns columns;
  const std::vector<std::int64_t> filling =
      labels::for_each_label_surface(v, picked, steps, [&](labels::LabelSurface& s) {
        auto mesh = std::make_shared<PyMesh>();
        mesh->mesh = std::move(s.mesh);
        mesh->isovalue = s.isovalue;
        const curvature::CurvatureField field =
            estimate_of(mesh, &s.indicator, py::none(), py::none(), py::none(),
                        py::float_(s.isovalue), py::none(), false, device)
                .field;
        const std::vector<measure::ObjectMeasures> objects = measure::object_measures(mesh->mesh, field);
        label.push_back(s.label.value);
        components.push_back(std::int64_t(objects.size()));
        columns.add(measure::total(objects));
        columns.genus.back() = measure::genus_sum(objects);  // -1 when a component is cut
      });
  warn_filling_labels(filling);  // as the CLI's measure --labels says it
  const py::ssize_t n = py::ssize_t(label.size());
  py::dict out = columns.dict();
  out["label"] = copy_array(label, {n});
  out["components"] = copy_array(components, {n});
  return out;
}

}  // namespace

void bind_measure(py::module_& m) {
  m.def("measure", &measure_of, py::arg("mesh"), py::arg("volume") = py::none(), py::kw_only(),
        py::arg("arrays") = py::none(), py::arg("iso") = py::none(), py::arg("device") = py::none(),
        R"doc(Shape measures of every connected component of `mesh` (isocurv measure; see
docs/measure.md), largest area first, as a dict of numpy arrays with one entry per component:
area, volume (enclosed; NaN for a component cut open), integral_H, integral_K (float64, world
units), euler_characteristic, genus (-1 when open), vertices, triangles, unmeasured_vertices
(int64), closed (uint8), gauss_bonnet_gap ((integral_K - 2 pi euler) / (2 pi max(1, |euler|)),
NaN when open), box ((n, 6): xmin, xmax, ymin, ymax, zmin, zmax), mesh_area (the mesh's own
triangles' area, where area is the smooth surface's), scale (the largest per-vertex smoothing
scale, 0 without a Scale array) and resolved (uint8: 0 when the component is smaller than
kResolvedExtent times that scale, its curvature integrals unreliable), curvature_genus
(1 - integral_K / (4 pi): the handles the curvature's integral implies, NaN when open) and
fine_handles (uint8: 1 when a resolved component's curvature_genus is under its genus by more
than 2 and a tenth, handles finer than the curvature scale). arrays: the mesh's
curvature (a dict as curvature() returns; H and K are read, Area and Unreliable when present);
None estimates curvature(mesh, volume) with its defaults (the volume estimator with a volume).
iso: the isovalue, with a volume, for a mesh without mesh.isovalue.)doc");

  m.def("measure_labels", &measure_labels_of, py::arg("volume"), py::arg("labels") = py::none(),
        py::kw_only(), py::arg("device") = py::none(),
        R"doc(Shape measures of every label of the label map `volume` (isocurv measure --labels;
see docs/labels.md): each label's surface at the half level of its own indicator (touching labels
each closed), its curvature from the volume estimator on that indicator. A dict of numpy arrays
with one entry per label, in ascending label order (or `labels`' order): label, components
(int64) and the sums over the label's components of what measure() returns (area, volume,
integral_H, integral_K, euler_characteristic, gauss_bonnet_gap, closed, vertices, triangles,
unmeasured_vertices, box). labels: None (all), an int or a sequence of ints; labels the volume
lacks, and labels that fill the volume's box (no surface), are left out with a UserWarning;
labels may be Python or numpy integers within +-16,777,215 (ValueError beyond). A float volume,
or more than 65,535 labels, raises isocurv.Error; none of `labels` in the volume raises
ValueError.)doc");
}

}  // namespace isocurv::python
