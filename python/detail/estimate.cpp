// The curvature estimate of the Python module and its arguments (python/detail/estimate.h).
#include "python/detail/estimate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "curvature/ao_scale.h"
#include "python/detail/arrays.h"

namespace isocurv::python {

curvature::Estimator estimator_of(const py::object& name, const char* arg) {
  if (name.is_none()) return curvature::Estimator::rusinkiewicz;
  if (!py::isinstance<py::str>(name))
    throw py::type_error(std::string(arg) + ": expected an estimator name (a str)");
  const std::string s = name.cast<std::string>();
  if (const auto e = curvature::estimator_from_name(s)) return *e;
  std::string names;
  for (const std::string& n : curvature::estimator_names())
    names += (names.empty() ? "" : ", ") + n;
  throw py::value_error(std::string(arg) + ": expected one of " + names + ", not '" + s + "'");
}

double scale_of(const py::object& scale) {
  if (scale.is_none()) return 0;
  if (py::isinstance<py::str>(scale)) {
    const std::string s = scale.cast<std::string>();
    if (s == "auto") return 0;
    throw py::value_error("scale: a positive number (world units) or 'auto', not '" + s + "'");
  }
  if (!py::isinstance<py::float_>(scale) && !py::isinstance<py::int_>(scale) &&
      !py::hasattr(scale, "__float__"))
    throw py::type_error("scale: expected a number (world units) or 'auto'");
  const double v = scale.cast<double>();
  if (!std::isfinite(v) || !(v > 0))
    throw py::value_error("scale: a positive number (world units) or 'auto', not " +
                          py::str(scale).cast<std::string>());
  return v;
}

curvature::NormalsSource normals_of(const py::object& normals) {
  if (normals.is_none()) return curvature::NormalsSource::automatic;
  if (!py::isinstance<py::str>(normals))
    throw py::type_error("normals: expected 'volume', 'mesh', 'area' or 'face-average'");
  const std::string s = normals.cast<std::string>();
  const std::optional<curvature::NormalsSource> n = curvature::normals_from_name(s);
  if (!n || *n == curvature::NormalsSource::automatic)  // "" is the command line's default only
    throw py::value_error("normals: expected 'volume', 'mesh', 'area' or 'face-average', not '" +
                          s + "'");
  return *n;
}

ao::Method ao_method_of(const py::object& method) {
  std::string names;
  for (const std::string& n : ao::method_names()) names += (names.empty() ? "'" : "', '") + n;
  names += "'";
  if (method.is_none()) return ao::Method::griffin;
  if (!py::isinstance<py::str>(method))
    throw py::type_error("ao_method: expected one of " + names + " (a str)");
  const std::string s = method.cast<std::string>();
  if (const auto m = ao::method_from_name(s)) return *m;
  throw py::value_error("ao_method: expected one of " + names + ", not '" + s + "'");
}

py::value_error request_error(const curvature::RequestError& e) {
  using P = curvature::RequestProblem;
  const std::string name = curvature::estimator_name(e.estimator);
  switch (e.problem) {
    case P::estimator_needs_volume:
      return py::value_error("estimator: '" + name +
                             "' needs the volume argument (it reads the volume's derivatives), "
                             "not a mesh alone");
    case P::normals_not_for_volume:
      return py::value_error("normals: applies to the mesh estimators; estimator='" + name +
                             "' takes its normals from the volume's gradient at scale");
    case P::scale_not_for_mesh:
      return py::value_error("scale: applies to estimator='volume' only");
    case P::volume_normals_need_volume:
      return py::value_error("normals: 'volume' needs the volume argument");
    case P::iso_not_for_mesh:
      return py::value_error("iso: applies to estimator='volume' only");
    case P::needs_isovalue:
      return py::value_error(
          "iso: estimator='" + name +
          "' needs the mesh's isovalue (meshes from isocurv.extract carry it as mesh.isovalue)");
    case P::not_positive:
      if (e.field == curvature::RequestField::ao_scale)
        return py::value_error("ao_scale: a positive number (world units)");
      break;
    case P::ao_needs_volume:
      return py::value_error(
          "ao_method: the ray casts ('raycast', 'raycast-cos') need the volume argument (they "
          "cast rays through it), not a mesh alone; 'griffin-exact', 'hattori' and 'prantl' "
          "work on meshes");
    case P::hattori_half_not_hattori:
      return py::value_error("hattori_half: applies to ao_method='hattori' only");
    case P::not_finite:
      break;
  }
  return py::value_error(e.what());  // "<argument>: <problem>"
}

py::dict report_dict(const curvature::EstimatorReport& r, const std::string& normals,
                     const volume::MeshNormals* vn) {
  py::dict d, params, chosen;
  d["estimator"] = r.estimator;
  for (const auto& [k, v] : r.parameters) params[k.c_str()] = v;
  for (const auto& [k, v] : r.notes) chosen[k.c_str()] = v;
  d["parameters"] = params;
  d["chosen"] = chosen;
  d["unreliable"] = r.unreliable;
  d["implausible"] = r.implausible;  // of those, flagged by the library's one rule
  d["normals"] = normals;
  if (vn) {
    py::dict f;
    f["opposed"] = vn->opposed;
    f["weak_gradient"] = vn->weak;
    f["caps"] = vn->caps;
    d["normal_fallbacks"] = f;
  }
  return d;
}

void check_mesh_in_volume(const Mesh& mesh, const volume::Volume& volume) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::array<double, 3> mlo{inf, inf, inf}, mhi{-inf, -inf, -inf};
  bool any = false;
  for (const Vec3f& p : mesh.positions) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
    any = true;
    for (int k = 0; k < 3; ++k) mlo[k] = std::min(mlo[k], double(p[k])), mhi[k] = std::max(mhi[k], double(p[k]));
  }
  if (!any || !volume.grid) return;
  std::array<double, 3> vlo{inf, inf, inf}, vhi{-inf, -inf, -inf};
  const openvdb::Coord a = volume.domain.min(), b = volume.domain.max();
  for (int c = 0; c < 8; ++c) {
    const openvdb::Vec3d w = volume.grid->transform().indexToWorld(
        openvdb::Vec3d(c & 1 ? b.x() : a.x(), c & 2 ? b.y() : a.y(), c & 4 ? b.z() : a.z()));
    for (int k = 0; k < 3; ++k) vlo[k] = std::min(vlo[k], w[k]), vhi[k] = std::max(vhi[k], w[k]);
  }
  const openvdb::Vec3d s = volume.spacing();
  const double voxel = std::max({s.x(), s.y(), s.z()});
  double beyond = 0;
  for (int k = 0; k < 3; ++k) beyond = std::max({beyond, vlo[k] - mlo[k], mhi[k] - vhi[k]});
  if (!(beyond > voxel * (1 + 1e-6))) return;
  auto box = [](const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
    std::string t;
    for (int k = 0; k < 3; ++k) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%s[%g, %g]", k ? " x " : "", lo[k], hi[k]);
      t += buf;
    }
    return t;
  };
  char far[32];
  std::snprintf(far, sizeof far, "%.3g", beyond / voxel);
  throw py::value_error("mesh: does not lie in the volume: its bounding box " + box(mlo, mhi) +
                        " reaches " + far + " voxels beyond the volume's world bounds " +
                        box(vlo, vhi) +
                        " (pass the volume the mesh was extracted from, with the same spacing "
                        "and origin)");
}

Estimated estimate_of(const std::shared_ptr<PyMesh>& mesh, const volume::Volume* volume,
                      py::object estimator, py::object scale, py::object normals_arg,
                      py::object iso, py::object ao_scale, bool cap, py::object device,
                      py::object ao_method, bool hattori_half) {
  const DeviceChoice dc = device_choice(device);
  // The arguments converted (TypeErrors, and a scale that is no positive number or 'auto'), then
  // the library's rules on them (curvature::resolve, the command line's), as ValueErrors naming
  // the argument.
  curvature::Request request;
  request.normals = normals_of(normals_arg);
  if (!estimator.is_none()) request.estimator = estimator_of(estimator, "estimator");
  request.scale_given = !scale.is_none();
  request.scale = scale_of(scale);
  if (!iso.is_none()) request.iso = number_of(iso, "iso");
  if (!ao_scale.is_none()) request.ao_scale = number_of(ao_scale, "ao_scale");
  if (!ao_method.is_none()) request.ao_method = ao_method_of(ao_method);
  request.hattori_half = hattori_half;
  curvature::Resolved r;
  try {
    r = curvature::resolve(request, volume != nullptr, mesh->isovalue);
  } catch (const curvature::RequestError& e) {
    throw request_error(e);
  }
  if (mesh->mesh.triangles.empty()) throw py::value_error("mesh: has no triangles");
  if (volume) check_mesh_in_volume(mesh->mesh, *volume);
  curvature::Options co;
  co.estimator = r.estimator;
  co.scale = r.scale;
  co.ao_scale = r.ao_scale ? *r.ao_scale : curvature::default_ao_scale(mesh->mesh);
  co.ao_method = r.ao_method;  // estimate_field's last step, as the command line's --ao-method
  co.hattori_half = r.hattori_half;
  curvature::CurvatureField field;
  curvature::EstimatorReport report;
  volume::MeshNormals vn;
  {
    py::gil_scoped_release release;
    vn = curvature::host_normals(r.normals, mesh->mesh, volume, cap);
    if (curvature::host_computed(r.normals)) co.vertex_normals = &vn.normals;
    std::lock_guard<std::mutex> lock(device_lock);
    field = curvature::estimate_field(mesh->mesh, {volume, r.isovalue},
                                      dc.reference ? nullptr : &opened_device(dc), co, &report);
  }
  const bool gradient = r.normals == curvature::NormalsSource::volume;
  return {std::move(field),
          report_dict(report, curvature::normals_report_name(r), gradient ? &vn : nullptr)};
}

float mesh_isovalue(const PyMesh& mesh, const py::object& iso, const std::string& why) {
  if (!iso.is_none()) return finite_number(iso, "iso");
  if (mesh.isovalue) return *mesh.isovalue;
  throw py::value_error("iso: " + why +
                        " needs the mesh's isovalue (meshes from isocurv.extract carry it as "
                        "mesh.isovalue; else pass iso=)");
}

curvature::CurvatureField field_for(const std::shared_ptr<PyMesh>& mesh,
                                    const volume::Volume* volume, const py::object& arrays,
                                    const py::object& iso, py::object device,
                                    std::initializer_list<const char*> needed) {
  if (arrays.is_none()) {
    // The CLI's default estimator: the volume's own with a volume, else Rusinkiewicz's.
    const py::object est_iso = volume ? iso : py::none();
    return estimate_of(mesh, volume, py::none(), py::none(), py::none(), est_iso, py::none(), false,
                       device)
        .field;
  }
  if (!py::isinstance<py::dict>(arrays))
    throw py::type_error("arrays: expected a dict of numpy arrays (as curvature() returns)");
  const py::dict d = arrays.cast<py::dict>();
  std::string missing;
  for (const char* name : needed)
    if (!d.contains(name)) missing += std::string(missing.empty() ? "" : ", ") + name;
  if (!missing.empty())
    throw py::value_error("arrays: lacks " + missing +
                          " (pass what isocurv.curvature() returns, or None to estimate it)");
  return field_from_dict(d, mesh->mesh.positions.size());
}

}  // namespace isocurv::python
