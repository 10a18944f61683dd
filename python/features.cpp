// The features area of the isocurv Python module: features (neighbourhood features at a radius
// of support).
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "core/error.h"
#include "core/mesh_measures.h"
#include "curvature/curvature_field.h"
#include "features/features.h"
#include "python/bind.h"
#include "python/detail/args.h"
#include "python/detail/arrays.h"
#include "python/detail/estimate.h"

namespace isocurv::python {

namespace {

/// radius= as the CLI's --radius: a number, a str "R[,R...]" (a trailing % is of the mesh's
/// bounding-box diagonal) or a sequence of those.
void radii_of(const py::object& radius, double diagonal, features::Options& fo) {
  auto bad = [](const std::string& item) {
    return py::value_error("radius: '" + item +
                           "' is not a positive number (world units, or N% of the bounding-box "
                           "diagonal)");
  };
  auto add_text = [&](const std::string& list) {
    try {
      features::parse_radii(list, diagonal, fo);
    } catch (const Error& e) {
      throw py::value_error(std::string("radius: ") + e.what());
    }
  };
  auto add = [&](const py::handle& item) {
    if (py::isinstance<py::str>(item)) return add_text(item.cast<std::string>());
    if (py::isinstance<py::bool_>(item) ||
        !(py::isinstance<py::float_>(item) || py::isinstance<py::int_>(item) ||
          py::hasattr(item, "__float__")))
      throw py::type_error("radius: expected a number (world units), a str such as '2%' or "
                           "'4,2%', or a list of those, not " + type_name_of(item));
    const double r = item.cast<double>();
    if (!(r > 0) || !std::isfinite(r)) throw bad(py::str(item).cast<std::string>());
    fo.radii.push_back(r);
    fo.radius_names.push_back(g_format(r));
  };
  if (py::isinstance<py::str>(radius) || !py::isinstance<py::sequence>(radius)) {
    add(radius);
  } else {
    for (const py::handle item : radius.cast<py::sequence>()) add(item);
  }
  if (fo.radii.empty()) throw py::value_error("radius: no radius given");
}

py::object features_of(const MeshArg& mesh_arg, const VolumeArg& volume_arg,
                       const py::object& radius, const py::object& names, const py::object& samples,
                       bool adaptive, const py::object& arrays, const py::object& iso,
                       py::object device) {
  const std::shared_ptr<PyMesh> mesh = mesh_of(mesh_arg, "mesh");
  const volume::Volume* volume = optional_volume(volume_arg, "volume");
  const DeviceChoice dc = device_choice(device);
  if (mesh->mesh.triangles.empty()) throw py::value_error("mesh: has no triangles");
  if (volume) check_mesh_in_volume(mesh->mesh, *volume);
  features::Options fo;
  if (!names.is_none()) {
    std::string list;
    if (py::isinstance<py::str>(names)) {
      list = names.cast<std::string>();
    } else if (py::isinstance<py::sequence>(names)) {
      for (const py::handle n : names.cast<py::sequence>()) {
        if (!py::isinstance<py::str>(n))
          throw py::type_error("features: expected names (str), not " + type_name_of(n));
        list += (list.empty() ? "" : ",") + n.cast<std::string>();
      }
    } else {
      throw py::type_error("features: expected 'all', a comma list or a list of names, not " +
                           type_name_of(names));
    }
    if (list != "all") {
      try {
        fo.features = features::parse_features(list);
      } catch (const Error& e) {
        throw py::value_error(std::string("features: ") + e.what());
      }
    }
  }
  for (features::Feature f : fo.features)
    if (f == features::Feature::Vr && !volume)
      throw py::value_error("features: Vr needs the volume argument (the volume integral "
                            "invariant reads the volume)");
  radii_of(radius, bounding_box_diagonal(mesh->mesh), fo);
  if (samples.is_none()) {
    fo.samples = volume ? 256 : 0;
  } else {
    if (!py::isinstance<py::int_>(samples) || py::isinstance<py::bool_>(samples))
      throw py::type_error("samples: expected an int (0, or N >= 32 with a volume)");
    const long n = samples.cast<long>();
    if (n != 0 && (n < 32 || n > 1 << 20))
      throw py::value_error("samples: 0 (the exact neighbourhoods) or N in 32..1048576, not " +
                            std::to_string(n));
    if (n > 0 && !volume)
      throw py::value_error("samples: sampled neighbourhoods trace the volume's isosurface; pass "
                            "volume= or samples=0");
    fo.samples = int(n);
  }
  fo.adaptive = adaptive;
  if (adaptive && fo.samples == 0)
    throw py::value_error("adaptive: applies to sampled neighbourhoods (samples=N with a volume)");
  if (volume) fo.isovalue = mesh_isovalue(*mesh, iso, "features with a volume");
  else if (!iso.is_none()) throw py::value_error("iso: applies with a volume only");
  const curvature::CurvatureField field =
      field_for(mesh, volume, arrays, iso, device, {"Normals", "Area"});
  features::FeatureField f;
  {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(device_lock);
    f = dc.reference ? features::compute(mesh->mesh, field, volume, fo)
                     : features::compute(mesh->mesh, field, volume, fo, opened_device(dc));
  }
  py::object out = curvature_arrays_type();
  const py::ssize_t n = py::ssize_t(mesh->mesh.positions.size());
  py::list array_names;
  for (const features::Array& a : f.arrays) {
    out[a.name.c_str()] = copy_array(a.values, {n});
    array_names.append(a.name);
  }
  out["FeatureBoundary"] = copy_array(f.boundary, {n});
  py::dict report;
  py::list radii;
  for (std::size_t i = 0; i < fo.radii.size(); ++i) {
    py::dict r;
    r["as_given"] = fo.radius_names[i];
    r["world"] = fo.radii[i];
    radii.append(r);
  }
  std::size_t boundary = 0;
  for (std::uint8_t b : f.boundary) boundary += b;
  report["radii"] = radii;
  report["arrays"] = array_names;
  report["mean_curvature_from"] = volume ? "volume integral invariant" : "surface samples";
  report["boundary_vertices"] = boundary;
  report["neighbourhoods"] = fo.samples > 0 ? "sampled" : "exact";
  report["samples"] = fo.samples;
  report["adaptive"] = fo.adaptive;
  report["samples_taken"] = f.samples_taken;
  report["traced_fraction"] = f.traced_fraction;
  out.attr("report") = report;
  return out;
}

}  // namespace

void bind_features(py::module_& m) {
  m.def("features", &features_of, py::arg("mesh"), py::arg("volume") = py::none(), py::kw_only(),
        py::arg("radius"), py::arg("features") = py::none(), py::arg("samples") = py::none(),
        py::arg("adaptive") = false, py::arg("arrays") = py::none(), py::arg("iso") = py::none(),
        py::arg("device") = py::none(),
        R"doc(Neighbourhood features of `mesh` at a radius of support (isocurv features; see
docs/features.md) as a CurvatureArrays: one (n,) float32 array per feature and radius, named as
in the files (LBE, NSV, Vr, H_ii, K_ii, SI_ii; with several radii suffixed _r<radius as given>,
H_ii_r2%), and FeatureBoundary (n,) uint8, 1 where some ball left what is known (the volume's
domain or an open boundary): its values are finite but biased. `.report`: {'radii' [{'as_given',
'world'}], 'arrays', 'mean_curvature_from', 'boundary_vertices', 'neighbourhoods', 'samples',
'adaptive', 'samples_taken', 'traced_fraction'}.

radius (required): world units, a str 'R[,R...]' where N% is of the mesh's bounding-box diagonal
(as --radius), or a list of those. features: 'all' (default: those the input allows; Vr needs
`volume`), a comma list or a list of names. samples: per vertex for LBE, NSV and K_ii; N >= 32
traces N/16 curves on the volume's isosurface, 0 the exact neighbourhoods; default 256 with a
volume, 0 without. adaptive: two-stage sampling (samples > 0). arrays: the mesh's curvature (a
dict as curvature() returns; Normals and Area are read); None estimates curvature(mesh, volume)
with its defaults. iso: the isovalue, with a volume, for a mesh without mesh.isovalue.)doc");
}

}  // namespace isocurv::python
