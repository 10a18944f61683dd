// The curvature area of the isocurv Python module: curvature, estimator_names and
// isocurv.Topology (a deforming mesh's curvature on prepared triangles).
#include <cstdint>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "curvature/ao_scale.h"
#include "curvature/curvature_field.h"
#include "curvature/estimate.h"
#include "curvature/estimator.h"
#include "curvature/field_stats.h"
#include "curvature/request.h"
#include "curvature/topology.h"
#include "python/bind.h"
#include "python/detail/args.h"
#include "python/detail/arrays.h"
#include "python/detail/estimate.h"

namespace isocurv::python {

namespace {

py::object curvature_of(const MeshArg& mesh_arg, const VolumeArg& volume_arg, py::object estimator,
                        py::object scale, py::object normals_arg, py::object iso,
                        py::object ao_scale, bool cap, py::object device, py::object ao_method,
                        bool hattori_half) {
  const std::shared_ptr<PyMesh> mesh = mesh_of(mesh_arg, "mesh");
  const volume::Volume* volume = optional_volume(volume_arg, "volume");
  Estimated e = estimate_of(mesh, volume, estimator, scale, normals_arg, iso, ao_scale, cap, device,
                            ao_method, hattori_half);
  return curvature_arrays(std::move(e.field), e.report);
}

/// isocurv.Topology: a mesh's triangles prepared once on the device, for the curvature of many
/// positions of the same connectivity (curvature/topology.h).
struct PyTopology {
  Device* device = nullptr;
  curvature::Topology topo;
  Mesh frame;       ///< the triangles and the latest positions (for ao_scale and host normals)
  std::mutex lock;  ///< one frame at a time (taken without the GIL, before device_lock)
};

std::shared_ptr<PyTopology> make_topology(const MeshArg& mesh_arg, py::object device) {
  const std::shared_ptr<PyMesh> mesh = mesh_of(mesh_arg, "mesh");
  const DeviceChoice dc = device_choice(device);
  if (dc.reference)
    throw py::value_error(
        "device: Topology runs on an OpenCL device ('reference' has no prepared path)");
  if (mesh->mesh.triangles.empty()) throw py::value_error("mesh: has no triangles");
  auto t = std::make_shared<PyTopology>();
  t->frame.triangles = mesh->mesh.triangles;
  t->frame.positions = mesh->mesh.positions;
  py::gil_scoped_release release;
  std::lock_guard<std::mutex> lock(device_lock);
  t->device = &opened_device(dc);
  t->topo = curvature::prepare(t->frame.triangles, t->frame.positions.size(), *t->device);
  return t;
}

py::object topology_curvature(PyTopology& t, const py::object& positions, py::object estimator,
                              py::object normals_arg, py::object ao_scale) {
  const curvature::Estimator e = estimator_of(estimator, "estimator");
  if (!curvature::has_prepared_path(e))
    throw py::value_error("estimator: Topology runs only " + curvature::prepared_estimator_names() +
                          "; " + curvature::no_prepared_path_reason(e));
  curvature::Request request;  // the library's rules, for a mesh without a volume
  request.estimator = e;
  request.normals = normals_of(normals_arg);
  if (!ao_scale.is_none()) request.ao_scale = number_of(ao_scale, "ao_scale");
  curvature::Resolved resolved;
  try {
    resolved = curvature::resolve(request, false);
  } catch (const curvature::RequestError& error) {
    if (error.problem == curvature::RequestProblem::volume_normals_need_volume)
      throw py::value_error("normals: Topology takes 'mesh', 'area' or 'face-average' (no volume)");
    throw request_error(error);
  }
  py::array_t<float, py::array::c_style | py::array::forcecast> p;
  try {
    p = positions.cast<decltype(p)>();
  } catch (const py::error_already_set&) {
    throw py::type_error("positions: expected a numeric (n, 3) array");
  } catch (const py::cast_error&) {
    throw py::type_error("positions: expected a numeric (n, 3) array");
  }
  const std::size_t n = t.frame.positions.size();
  if (p.ndim() != 2 || p.shape(1) != 3 || std::size_t(p.shape(0)) != n)
    throw py::value_error("positions: expected shape (" + std::to_string(n) +
                          ", 3) (one per vertex of the prepared mesh)");
  curvature::Options co;
  co.estimator = e;
  curvature::CurvatureField field;
  curvature::EstimatorReport r;
  r.estimator = curvature::estimator_name(e);
  {
    py::gil_scoped_release release;  // p stays referenced, so its data stays valid
    std::lock_guard<std::mutex> frame_lock(t.lock);
    std::memcpy(static_cast<void*>(t.frame.positions.data()), p.data(), n * sizeof(Vec3f));
    co.ao_scale = resolved.ao_scale ? *resolved.ao_scale : curvature::default_ao_scale(t.frame);
    r.parameters.emplace_back("ao_scale", co.ao_scale);
    const volume::MeshNormals averaged = curvature::host_normals(resolved.normals, t.frame, nullptr);
    if (curvature::host_computed(resolved.normals)) co.vertex_normals = &averaged.normals;
    std::lock_guard<std::mutex> lock(device_lock);
    if (e == curvature::Estimator::rusinkiewicz) {
      curvature::estimate(t.frame.positions, t.topo, *t.device, co, field);
    } else {
      curvature::upload_positions(t.frame.positions, t.topo);
      curvature::estimate_resident(e, t.topo, *t.device, co, field);
      for (std::uint8_t u : field.unreliable) r.unreliable += u;
    }
    // The library's one rule for unmeasured vertices, as estimate_field applies it.
    r.implausible = curvature::flag_implausible(t.frame, field);
    r.unreliable += r.implausible;
  }
  return curvature_arrays(std::move(field), report_dict(r, curvature::normals_name(resolved.normals), nullptr));
}

}  // namespace

void bind_curvature(py::module_& m) {
  m.def(
      "curvature", &curvature_of, py::arg("mesh"), py::arg("volume") = py::none(), py::kw_only(),
      py::arg("estimator") = py::none(), py::arg("scale") = py::none(),
      py::arg("normals") = py::none(), py::arg("iso") = py::none(),
      py::arg("ao_scale") = py::none(), py::arg("cap") = false, py::arg("device") = py::none(),
      py::arg("ao_method") = py::none(), py::arg("hattori_half") = false,
      R"doc(Per-vertex curvature of `mesh` as a CurvatureArrays (a dict) of numpy arrays named as in
the files: Normals (n, 3), Area, k1, k2 (k1 >= k2), dir1, dir2 (n, 3), H, K, dcurv (n, 4),
ShapeIndex, Curvedness, AO (n,), Boundary (n,) uint8, Unreliable (n,) uint8: the unmeasured-vertex
mask, 1 where the estimator could not measure (there every other array holds a placeholder, zero
curvature, not NaN: leave those vertices out, as stats.json does); an estimator fills only the
arrays it can. `.report` says what was used:
{'estimator', 'parameters' (e.g. {'scale': 1.5, 'ao_scale': 2.0}, world units), 'chosen'
({'scale': 'auto'|'given'}), 'unreliable' (count), 'normals'[, 'normal_fallbacks']}.

estimator: one of isocurv.estimator_names() (the CLI's --estimator): 'volume' (the volume's own
derivatives at `scale`, per vertex Scale array; the default when `volume` is given and `normals`
is not; needs the mesh's isovalue: mesh.isovalue for meshes from extract, else iso=),
'rusinkiewicz' (the default otherwise), or the other mesh estimators
batagelo, prantl3, prantl2, quadric, cubic, sampling, meyer. scale: the volume estimator's
Gaussian sigma in world units, or 'auto'/None (from the data); an error with a mesh estimator.
normals (mesh estimators): 'volume' (the gradient of `volume`, face normals where it cannot be
trusted; the default with a volume), 'mesh' (the faces, Max's weights; the default without),
'area' or 'face-average'; an error with estimator='volume'. cap=True when the mesh was
extracted with cap=True. ao_scale: ambient-occlusion radius in world units (default 4 mean edge
lengths). ao_method: how the AO array is computed, as the CLI's --ao-method: 'griffin' (the
default), 'griffin-exact', 'hattori', 'prantl', or the ray casts 'raycast', 'raycast-cos' (need
`volume`); hattori_half=True: hattori's umbilic mean. Normals point out of the object, so a solid sphere of radius R has k1 = k2 = H = +1/R.
A mesh that does not lie in `volume` (its bounding box more than a voxel beyond the volume's
world bounds: a mesh of another volume, or other spacing or origin) raises ValueError.
Wrong combinations raise ValueError naming the argument.)doc");

  m.def("estimator_names", &curvature::estimator_names,
        "The names curvature(estimator=...) takes, as the CLI's --estimator.");

  py::class_<PyTopology, std::shared_ptr<PyTopology>>(
      m, "Topology",
      R"doc(Topology(mesh, device=None): the mesh's triangles prepared once on the OpenCL device
(adjacency built and uploaded), for the curvature of a deforming mesh whose connectivity never
changes. topology.curvature(positions) then uploads only the (n, 3) positions; the result is
bit-identical to isocurv.curvature(isocurv.Mesh(positions, mesh.triangles), normals=...,
estimator=...) on the same device. One call at a time (calls are serialised).)doc")
      .def(py::init(&make_topology), py::arg("mesh"), py::kw_only(), py::arg("device") = py::none())
      .def("curvature", &topology_curvature, py::arg("positions"), py::kw_only(),
           py::arg("estimator") = py::none(), py::arg("normals") = py::none(),
           py::arg("ao_scale") = py::none(),
           R"doc(Curvature of the prepared triangles at `positions` ((n, 3), n the mesh's vertex
count; converted to float32) as a CurvatureArrays with .report, as isocurv.curvature.
estimator: 'rusinkiewicz' (default), 'batagelo', 'prantl3' or 'prantl2' (those with a prepared
path); normals: 'mesh' (default), 'area' or 'face-average'; ao_scale: default 4 mean edge
lengths of these positions.)doc")
      .def_property_readonly("vertex_count",
                             [](const PyTopology& t) { return t.frame.positions.size(); })
      .def_property_readonly("triangle_count",
                             [](const PyTopology& t) { return t.frame.triangles.size(); })
      .def("__repr__", [](const PyTopology& t) {
        return "<isocurv.Topology " + std::to_string(t.frame.positions.size()) + " vertices, " +
               std::to_string(t.frame.triangles.size()) + " triangles>";
      });
}

}  // namespace isocurv::python
