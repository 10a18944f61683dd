// The isocurv Python module (pybind11): the same library calls as the command line, on numpy
// arrays. Volumes and meshes are opaque objects; mesh vertices and triangles are numpy views of
// the C++ arrays (no copy), curvature arrays numpy views of the estimated field.
//
// Threading: the GIL is released while a call computes, loads or writes; calls that use the
// OpenCL device are serialised by one lock (a Device is for one thread at a time).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "core/cl_device.h"
#include "core/error.h"
#include "core/mesh.h"
#include "core/mesh_measures.h"
#include "core/program_cache.h"
#include "curvature/ao_scale.h"
#include "curvature/curvature_field.h"
#include "curvature/estimate.h"
#include "curvature/estimator.h"
#include "curvature/face_average_normals.h"
#include "curvature/reference.h"
#include "curvature/topology.h"
#include "io/compression.h"
#include "io/field_arrays.h"
#include "io/mesh_file.h"
#include "mc/extract.h"
#include "mc/extract_reference.h"
#include "mc/mesh_check.h"
#include "mc/options.h"
#include "volume/from_dense.h"
#include "volume/gradient_normals.h"
#include "volume/load.h"
#include "volume/volume.h"

namespace py = pybind11;
using namespace isocurv;

namespace {

std::mutex device_lock;  ///< one device call at a time, across Python threads

/// --device as the CLI takes it: None (the default device), an index, or "reference".
struct DeviceChoice {
  bool reference = false;
  int index = -1;
};

DeviceChoice device_choice(const py::object& device) {
  DeviceChoice c;
  if (device.is_none()) return c;
  if (py::isinstance<py::str>(device)) {
    const std::string s = device.cast<std::string>();
    if (s == "reference") {
      c.reference = true;
      return c;
    }
    throw py::value_error("device: expected None, a device number or 'reference', not '" + s + "'");
  }
  if (py::isinstance<py::int_>(device)) {
    c.index = device.cast<int>();
    if (c.index < 0) throw py::value_error("device: a device number is >= 0");
    return c;
  }
  throw py::type_error("device: expected None, an int or 'reference'");
}

Device& opened_device(const DeviceChoice& c) {
  static std::map<int, std::shared_ptr<Device>> opened;
  if (c.index < 0) return Device::default_device();
  auto& d = opened[c.index];
  if (!d) d = Device::open(c.index);
  return *d;
}

/// A Mesh shared between Python objects and the numpy views of its arrays.
struct PyMesh {
  Mesh mesh;
  std::optional<float> isovalue;  ///< set by extract (the volume estimator needs it)
};

volume::Inside inside_of(const std::string& s) {
  if (s == "above") return volume::Inside::Above;
  if (s == "below") return volume::Inside::Below;
  throw py::value_error("inside: expected 'above' or 'below', not '" + s + "'");
}

std::array<double, 3> triple(const py::object& o, const char* name) {
  std::array<double, 3> v{};
  try {
    const auto seq = o.cast<std::vector<double>>();
    if (seq.size() != 3)
      throw py::value_error(std::string(name) + ": expected 3 numbers (x, y, z)");
    for (int i = 0; i < 3; ++i) v[i] = seq[i];
  } catch (const py::cast_error&) {
    throw py::type_error(std::string(name) + ": expected a sequence of 3 numbers (x, y, z)");
  }
  return v;
}

/// Converts a C-contiguous 3-D array of one voxel type to floats, X fastest.
template <class T>
std::vector<float> to_floats(const py::array& a) {
  const auto* p = static_cast<const T*>(a.data());
  std::vector<float> out(static_cast<std::size_t>(a.size()));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<float>(p[i]);
  return out;
}

volume::Volume from_array(const py::array& array, const py::object& spacing,
                          const py::object& origin, const std::string& inside) {
  if (array.ndim() != 3)
    throw py::value_error("array: expected a 3-D array indexed [z, y, x], got " +
                          std::to_string(array.ndim()) + " dimensions");
  if (!(array.flags() & py::array::c_style))
    throw py::value_error(
        "array: must be C-contiguous (numpy.ascontiguousarray(array) makes a copy that is)");
  const std::array<double, 3> s = triple(spacing, "spacing"), o = triple(origin, "origin");
  for (double x : s)
    if (!(x > 0) || !std::isfinite(x))
      throw py::value_error("spacing: every value must be positive and finite");
  for (double x : o)
    if (!std::isfinite(x)) throw py::value_error("origin: every value must be finite");
  const volume::Inside side = inside_of(inside);
  const py::dtype dt = array.dtype();
  std::vector<float> values;
  std::string type;
  const char kind = dt.kind();
  const auto size = dt.itemsize();
  if (kind == 'u' && size == 1)
    values = to_floats<std::uint8_t>(array), type = "uint8";
  else if (kind == 'i' && size == 1)
    values = to_floats<std::int8_t>(array), type = "int8";
  else if (kind == 'u' && size == 2)
    values = to_floats<std::uint16_t>(array), type = "uint16";
  else if (kind == 'i' && size == 2)
    values = to_floats<std::int16_t>(array), type = "int16";
  else if (kind == 'u' && size == 4)
    values = to_floats<std::uint32_t>(array), type = "uint32";
  else if (kind == 'i' && size == 4)
    values = to_floats<std::int32_t>(array), type = "int32";
  else if (kind == 'f' && size == 4)
    values = to_floats<float>(array), type = "float";
  else if (kind == 'f' && size == 8)
    values = to_floats<double>(array), type = "double";
  else
    throw py::type_error(
        "array: voxel type " + py::str(py::object(dt)).cast<std::string>() +
        " is not one isocurv loads (uint8 int8 uint16 int16 uint32 int32 float32 float64)");
  if (!dt.attr("isnative").cast<bool>())
    throw py::type_error(
        "array: byte order must be the machine's (use array.astype(native dtype))");
  const std::array<int, 3> dims = {int(array.shape(2)), int(array.shape(1)), int(array.shape(0))};
  py::gil_scoped_release release;
  auto xform = openvdb::math::Transform::createLinearTransform(1.0);
  xform->preScale(openvdb::Vec3d(s[0], s[1], s[2]));
  xform->postTranslate(openvdb::Vec3d(o[0], o[1], o[2]));
  volume::DenseSource src;
  src.path = "<array>";
  src.format = "array";
  src.voxel_type = type;
  src.inside = side;
  return volume::from_dense(values.data(), dims, xform, src);
}

/// A numpy view of `n` rows of `cols` elements of T at `data`, kept alive by `base`.
template <class T>
py::array view(const T* data, std::size_t n, std::size_t cols, py::handle base) {
  if (n == 0)
    return cols == 1 ? py::array_t<T>(std::vector<py::ssize_t>{0})
                     : py::array_t<T>(std::vector<py::ssize_t>{0, py::ssize_t(cols)});
  if (cols == 1) return py::array_t<T>({n}, {sizeof(T)}, data, base);
  return py::array_t<T>({n, cols}, {cols * sizeof(T), sizeof(T)}, data, base);
}

/// The field's non-empty arrays as numpy views of one heap copy of the field (owned by a capsule),
/// stored by name into `out` (a dict, or a CurvatureArrays).
py::object field_dict(curvature::CurvatureField&& field, py::object out = py::dict()) {
  auto* owned = new curvature::CurvatureField(std::move(field));
  py::capsule base(owned, [](void* p) { delete static_cast<curvature::CurvatureField*>(p); });
  io::for_each_array(*owned, [&](const char* name, const auto& v) {
    if (v.empty()) return;
    using E = typename std::decay_t<decltype(v)>::value_type;
    constexpr int comps = io::components_of<E>();
    if constexpr (comps == 1)
      out[name] = view(v.data(), v.size(), 1, base);
    else
      out[name] = view(v.data()->data(), v.size(), comps, base);
  });
  return out;
}

/// A dict of arrays (names as in the files) -> CurvatureField, each checked against `vertices`.
curvature::CurvatureField field_from_dict(const py::dict& arrays, std::size_t vertices) {
  curvature::CurvatureField f;
  std::size_t used = 0;
  io::for_each_array(f, [&](const char* name, auto& v) {
    if (!arrays.contains(name)) return;
    ++used;
    using E = typename std::decay_t<decltype(v)>::value_type;
    constexpr int comps = io::components_of<E>();
    using S = std::conditional_t<std::is_same_v<E, std::uint8_t>, std::uint8_t, float>;
    py::array_t<S, py::array::c_style | py::array::forcecast> a;
    try {
      a = arrays[name].template cast<py::array_t<S, py::array::c_style | py::array::forcecast>>();
    } catch (const py::error_already_set&) {
      throw py::type_error(std::string("arrays['") + name + "']: expected a numeric array");
    } catch (const py::cast_error&) {
      throw py::type_error(std::string("arrays['") + name + "']: expected a numeric array");
    }
    const bool ok = comps == 1 ? (a.ndim() == 1 || (a.ndim() == 2 && a.shape(1) == 1))
                               : (a.ndim() == 2 && a.shape(1) == comps);
    if (!ok || std::size_t(a.shape(0)) != vertices)
      throw py::value_error(
          std::string("arrays['") + name + "']: expected shape (" + std::to_string(vertices) +
          (comps == 1 ? "," : ", " + std::to_string(comps)) + ") (one per vertex)");
    v.resize(vertices);
    std::memcpy(static_cast<void*>(v.data()), a.data(), vertices * sizeof(E));
  });
  if (used != arrays.size()) {
    // The others (Unreliable, Scale, features' arrays, ...): one value per vertex, written under
    // their names after the curvature arrays.
    for (auto item : arrays) {
      const std::string key = py::str(item.first);
      bool known = false;
      io::for_each_array(f, [&](const char* name, auto&) { known = known || key == name; });
      if (known) continue;
      py::array_t<float, py::array::c_style | py::array::forcecast> a;
      try {
        a = py::reinterpret_borrow<py::object>(item.second)
                .cast<py::array_t<float, py::array::c_style | py::array::forcecast>>();
      } catch (const py::error_already_set&) {
        throw py::type_error("arrays['" + key + "']: expected a numeric array");
      } catch (const py::cast_error&) {
        throw py::type_error("arrays['" + key + "']: expected a numeric array");
      }
      if (a.ndim() != 1 || std::size_t(a.shape(0)) != vertices)
        throw py::value_error("arrays['" + key + "']: expected shape (" +
                              std::to_string(vertices) +
                              ",) (one per vertex; arrays other than Normals Area k1 k2 dir1 "
                              "dir2 H K dcurv ShapeIndex Curvedness AO Boundary are scalars)");
      if (key == "Unreliable") {
        f.unreliable.resize(vertices);
        for (std::size_t i = 0; i < vertices; ++i) f.unreliable[i] = a.data()[i] != 0;
      } else {
        f.extra.push_back({key, std::vector<float>(a.data(), a.data() + vertices)});
      }
    }
  }
  return f;
}

std::shared_ptr<PyMesh> mesh_from_arrays(const py::object& vertices, const py::object& triangles) {
  py::array_t<float, py::array::c_style | py::array::forcecast> v;
  py::array_t<std::int64_t, py::array::c_style | py::array::forcecast> t;
  try {
    v = vertices.cast<decltype(v)>();
  } catch (const py::error_already_set&) {
    throw py::type_error("vertices: expected a numeric (n, 3) array");
  } catch (const py::cast_error&) {
    throw py::type_error("vertices: expected a numeric (n, 3) array");
  }
  try {
    t = triangles.cast<decltype(t)>();
  } catch (const py::error_already_set&) {
    throw py::type_error("triangles: expected an integer (m, 3) array");
  } catch (const py::cast_error&) {
    throw py::type_error("triangles: expected an integer (m, 3) array");
  }
  if (v.ndim() != 2 || v.shape(1) != 3) throw py::value_error("vertices: expected shape (n, 3)");
  if (t.ndim() != 2 || t.shape(1) != 3) throw py::value_error("triangles: expected shape (m, 3)");
  auto m = std::make_shared<PyMesh>();
  const std::size_t n = std::size_t(v.shape(0));
  m->mesh.positions.resize(n);
  std::memcpy(static_cast<void*>(m->mesh.positions.data()), v.data(), n * sizeof(Vec3f));
  const auto* ti = t.data();
  m->mesh.triangles.resize(std::size_t(t.shape(0)));
  for (std::size_t i = 0; i < m->mesh.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const std::int64_t idx = ti[3 * i + k];
      if (idx < 0 || std::uint64_t(idx) >= n)
        throw py::value_error("triangles: index " + std::to_string(idx) + " out of range (" +
                              std::to_string(n) + " vertices)");
      m->mesh.triangles[i][k] = std::uint32_t(idx);
    }
  return m;
}

/// isocurv.CurvatureArrays: the dict subclass curvature() returns (made at module import).
py::handle curvature_arrays_type;

/// The estimator called `name` (ValueError naming `arg` and listing the names otherwise).
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

/// scale= as the CLI's --scale: None or 'auto' (0: chosen from the data) or a positive number.
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

/// normals= for the mesh estimators: None (the default), 'volume', 'mesh', 'area' or
/// 'face-average' (the CLI's --normals).
std::string normals_of(const py::object& normals) {
  if (normals.is_none()) return "";
  if (!py::isinstance<py::str>(normals))
    throw py::type_error("normals: expected 'volume', 'mesh', 'area' or 'face-average'");
  const std::string s = normals.cast<std::string>();
  if (s != "volume" && s != "mesh" && s != "area" && s != "face-average")
    throw py::value_error("normals: expected 'volume', 'mesh', 'area' or 'face-average', not '" +
                          s + "'");
  return s;
}

/// Host-side vertex normals for normals='area' / 'face-average' (empty for 'mesh': the
/// estimator's own Max-weighted normals).
std::vector<Vec3f> mesh_normals(const Mesh& mesh, const std::string& source) {
  if (source == "area") return area_weighted_normals(mesh);
  if (source == "face-average") return curvature::face_average_normals(mesh);
  return {};
}

/// ao_scale= : None (4 mean edge lengths of `mesh`) or a radius in world units.
/// A Python number as a finite float (TypeError / ValueError naming `arg` otherwise).
float finite_number(const py::object& o, const char* arg) {
  float v = 0;
  try {
    v = o.cast<float>();
  } catch (const py::cast_error&) {
    throw py::type_error(std::string(arg) + ": expected a number");
  }
  if (!std::isfinite(v)) throw py::value_error(std::string(arg) + ": must be a finite number");
  return v;
}

/// ao_scale= : None (nothing: 4 mean edge lengths of the mesh) or a positive radius, world units.
std::optional<float> ao_scale_of(const py::object& ao_scale) {
  if (ao_scale.is_none()) return std::nullopt;
  const float v = finite_number(ao_scale, "ao_scale");
  if (!(v > 0)) throw py::value_error("ao_scale: a positive number (world units)");
  return v;
}

/// What a curvature call used, as CurvatureArrays.report: {"estimator", "parameters" {name:
/// value}, "chosen" {name: 'auto'|'given'}, "unreliable", "normals"[, "normal_fallbacks"]}.
py::dict report_dict(const curvature::EstimatorReport& r, const std::string& normals,
                     const volume::MeshNormals* vn) {
  py::dict d, params, chosen;
  d["estimator"] = r.estimator;
  for (const auto& [k, v] : r.parameters) params[k.c_str()] = v;
  for (const auto& [k, v] : r.notes) chosen[k.c_str()] = v;
  d["parameters"] = params;
  d["chosen"] = chosen;
  d["unreliable"] = r.unreliable;
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

/// A CurvatureArrays of the field's arrays carrying `report`.
py::object curvature_arrays(curvature::CurvatureField&& field, py::dict report) {
  py::object out = field_dict(std::move(field), curvature_arrays_type());
  out.attr("report") = report;
  return out;
}

py::object curvature_of(const std::shared_ptr<PyMesh>& mesh, const volume::Volume* volume,
                        py::object estimator, py::object scale, py::object normals_arg,
                        py::object iso, py::object ao_scale, bool cap, py::object device) {
  const DeviceChoice dc = device_choice(device);
  curvature::Options co;
  const std::string given = normals_of(normals_arg);
  // The CLI's default (app/pipeline.cpp default_estimator): volume when there is a volume and no
  // normals were asked for.
  co.estimator = estimator.is_none() && volume && given.empty()
                     ? curvature::Estimator::volume
                     : estimator_of(estimator, "estimator");
  const bool mesh_estimator = !curvature::needs_volume(co.estimator);
  const std::string name = curvature::estimator_name(co.estimator);
  // The CLI's rules (app/pipeline.cpp estimate_curvature), as ValueErrors naming the argument.
  if (!mesh_estimator && !volume)
    throw py::value_error("estimator: '" + name +
                          "' needs the volume argument (it reads the volume's derivatives), not "
                          "a mesh alone");
  if (!mesh_estimator && !given.empty())
    throw py::value_error("normals: applies to the mesh estimators; estimator='" + name +
                          "' takes its normals from the volume's gradient at scale");
  if (mesh_estimator && !scale.is_none())
    throw py::value_error("scale: applies to estimator='volume' only");
  co.scale = scale_of(scale);
  const std::string source = !mesh_estimator ? "volume estimator"
                             : given.empty() ? (volume ? "volume" : "mesh")
                                             : given;
  if (source == "volume" && !volume)
    throw py::value_error("normals: 'volume' needs the volume argument");
  float isovalue = 0;
  if (!mesh_estimator) {
    if (!iso.is_none())
      isovalue = finite_number(iso, "iso");
    else if (mesh->isovalue)
      isovalue = *mesh->isovalue;
    else
      throw py::value_error(
          "iso: estimator='" + name +
          "' needs the mesh's isovalue (meshes from isocurv.extract carry it as mesh.isovalue)");
    if (!std::isfinite(isovalue)) throw py::value_error("iso: must be a finite number");
  } else if (!iso.is_none()) {
    throw py::value_error("iso: applies to estimator='volume' only");
  }
  if (mesh->mesh.triangles.empty()) throw py::value_error("mesh: has no triangles");
  const std::optional<float> ao = ao_scale_of(ao_scale);
  co.ao_scale = ao ? *ao : curvature::default_ao_scale(mesh->mesh);
  curvature::CurvatureField field;
  curvature::EstimatorReport report;
  volume::MeshNormals vn;
  std::vector<Vec3f> averaged;
  {
    py::gil_scoped_release release;
    if (source == "volume") {
      vn = volume::gradient_normals_for_mesh(*volume, mesh->mesh, cap);
      co.vertex_normals = &vn.normals;
    } else if (source == "area" || source == "face-average") {
      averaged = mesh_normals(mesh->mesh, source);
      co.vertex_normals = &averaged;
    }
    std::lock_guard<std::mutex> lock(device_lock);
    field = curvature::estimate_field(mesh->mesh, {volume, isovalue},
                                      dc.reference ? nullptr : &opened_device(dc), co, &report);
  }
  return curvature_arrays(std::move(field),
                          report_dict(report, source, source == "volume" ? &vn : nullptr));
}

/// isocurv.Topology: a mesh's triangles prepared once on the device, for the curvature of many
/// positions of the same connectivity (curvature/topology.h).
struct PyTopology {
  Device* device = nullptr;
  curvature::Topology topo;
  Mesh frame;       ///< the triangles and the latest positions (for ao_scale and host normals)
  std::mutex lock;  ///< one frame at a time (taken without the GIL, before device_lock)
};

std::shared_ptr<PyTopology> make_topology(const std::shared_ptr<PyMesh>& mesh, py::object device) {
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
  if (e != curvature::Estimator::rusinkiewicz && e != curvature::Estimator::batagelo &&
      e != curvature::Estimator::prantl3 && e != curvature::Estimator::prantl2)
    throw py::value_error(
        "estimator: Topology runs rusinkiewicz, batagelo, prantl3 or prantl2 (the estimators "
        "with a prepared-topology path), not '" +
        std::string(curvature::estimator_name(e)) + "'");
  std::string source = normals_of(normals_arg);
  if (source == "volume")
    throw py::value_error("normals: Topology takes 'mesh', 'area' or 'face-average' (no volume)");
  if (source.empty()) source = "mesh";
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
  const std::optional<float> ao = ao_scale_of(ao_scale);
  curvature::Options co;
  co.estimator = e;
  curvature::CurvatureField field;
  curvature::EstimatorReport r;
  r.estimator = curvature::estimator_name(e);
  {
    py::gil_scoped_release release;  // p stays referenced, so its data stays valid
    std::lock_guard<std::mutex> frame_lock(t.lock);
    std::memcpy(static_cast<void*>(t.frame.positions.data()), p.data(), n * sizeof(Vec3f));
    co.ao_scale = ao ? *ao : curvature::default_ao_scale(t.frame);
    r.parameters.emplace_back("ao_scale", co.ao_scale);
    const std::vector<Vec3f> averaged = mesh_normals(t.frame, source);
    if (!averaged.empty()) co.vertex_normals = &averaged;
    std::lock_guard<std::mutex> lock(device_lock);
    if (e == curvature::Estimator::rusinkiewicz) {
      curvature::estimate(t.frame.positions, t.topo, *t.device, co, field);
    } else {
      curvature::upload_positions(t.frame.positions, t.topo);
      curvature::estimate_resident(e, t.topo, *t.device, co, field);
      for (std::uint8_t u : field.unreliable) r.unreliable += u;
    }
  }
  return curvature_arrays(std::move(field), report_dict(r, source, nullptr));
}

}  // namespace

PYBIND11_MODULE(isocurv, m) {
  m.doc() =
      "isocurv: isosurfaces and their curvature from volumes (OpenVDB, OpenCL, VTK).\n\n"
      "  v = isocurv.load('ct.nrrd')                 # or isocurv.from_array(a, spacing=(1, 1, "
      "1.4))\n"
      "  mesh = isocurv.extract(v, iso=40)           # mesh.vertices (n, 3) float32, "
      "mesh.triangles (m, 3) uint32\n"
      "  arrays = isocurv.curvature(mesh, volume=v)  # {'H': ..., 'K': ..., 'k1': ..., 'dir1': "
      "..., ...}\n"
      "  isocurv.write_mesh('ct.vtp', mesh, arrays)\n"
      "  topo = isocurv.Topology(mesh)               # a deforming mesh: "
      "topo.curvature(positions)\n\n"
      "Errors raise isocurv.Error (a RuntimeError) with the command line's one-line message; "
      "wrong\n"
      "argument types raise TypeError, wrong shapes or values ValueError, naming the argument.";
  static py::exception<Error> error_type(m, "Error", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      error_type(e.what());
    } catch (const cl::Error& e) {
      error_type(
          (std::string("OpenCL: ") + e.what() + " (" + cl_error_name(e.err()) + ")").c_str());
    }
  });
  set_program_cache_warnings(true);

  {
    py::dict ns;
    ns["__module__"] = "isocurv";
    ns["__doc__"] =
        "The dict of numpy arrays curvature() returns, with .report: the estimator, its "
        "parameters and the unreliable count.";
    py::object dict_type =
        py::reinterpret_borrow<py::object>(reinterpret_cast<PyObject*>(&PyDict_Type));
    py::object cls = py::module_::import("builtins")
                         .attr("type")("CurvatureArrays", py::make_tuple(dict_type), ns);
    m.attr("CurvatureArrays") = cls;
    curvature_arrays_type = cls;  // kept alive by the module
  }

  py::class_<volume::Volume>(
      m, "Volume",
      "A loaded volume (an OpenVDB float grid with its spacing, origin and value "
      "statistics). Made by isocurv.load or isocurv.from_array.")
      .def_property_readonly(
          "shape",
          [](const volume::Volume& v) {
            const auto d = v.domain.dim();
            return py::make_tuple(d.z(), d.y(), d.x());
          },
          "Voxel counts (z, y, x) of the data domain, as numpy indexes it")
      .def_property_readonly(
          "spacing",
          [](const volume::Volume& v) {
            const auto s = v.spacing();
            return py::make_tuple(s.x(), s.y(), s.z());
          },
          "World units per voxel along x, y, z")
      .def_property_readonly(
          "origin",
          [](const volume::Volume& v) {
            const auto o = v.origin();
            return py::make_tuple(o.x(), o.y(), o.z());
          },
          "World position of voxel (0, 0, 0)")
      .def_property_readonly(
          "value_range",
          [](const volume::Volume& v) { return py::make_tuple(v.stats.min, v.stats.max); },
          "(min, max) of the finite voxel values")
      .def_property_readonly(
          "suggested_isovalue", [](const volume::Volume& v) { return v.stats.suggested_isovalue; },
          "0 for level sets, else Otsu's threshold (the default iso of extract)")
      .def_property_readonly(
          "inside",
          [](const volume::Volume& v) {
            return v.inside == volume::Inside::Above ? "above" : "below";
          },
          "'above': the object is where values exceed the isovalue; 'below' for level sets")
      .def_property_readonly(
          "voxel_type", [](const volume::Volume& v) { return v.voxel_type; },
          "The voxel type in the file or array, e.g. 'uint16'")
      .def_property_readonly("path", [](const volume::Volume& v) { return v.path; })
      .def("__repr__", [](const volume::Volume& v) {
        const auto d = v.domain.dim();
        return "<isocurv.Volume " + std::to_string(d.x()) + "x" + std::to_string(d.y()) + "x" +
               std::to_string(d.z()) + " " + v.voxel_type + " '" + v.path + "'>";
      });

  py::class_<PyMesh, std::shared_ptr<PyMesh>>(
      m, "Mesh",
      "A fused, indexed triangle mesh in world coordinates. Mesh(vertices, triangles) copies (n, "
      "3) "
      "vertices and (m, 3) vertex indices; .vertices and .triangles are numpy views of the mesh "
      "(no copy; writing to them changes the mesh; they keep it alive).")
      .def(py::init(&mesh_from_arrays), py::arg("vertices"), py::arg("triangles"))
      .def_property_readonly(
          "vertices",
          [](py::object self) {
            auto& me = self.cast<PyMesh&>();
            const float* p = me.mesh.positions.empty() ? nullptr : me.mesh.positions.data()->data();
            return view(p, me.mesh.positions.size(), 3, self);
          },
          "(n, 3) float32 view of the vertex positions")
      .def_property_readonly(
          "triangles",
          [](py::object self) {
            auto& me = self.cast<PyMesh&>();
            const std::uint32_t* p =
                me.mesh.triangles.empty() ? nullptr : me.mesh.triangles.data()->data();
            return view(p, me.mesh.triangles.size(), 3, self);
          },
          "(m, 3) uint32 view of the triangles' vertex indices (normals point out of the object)")
      .def_property(
          "isovalue",
          [](const PyMesh& me) {
            return me.isovalue ? py::object(py::float_(*me.isovalue)) : py::object(py::none());
          },
          [](PyMesh& me, py::object v) {
            if (v.is_none())
              me.isovalue.reset();
            else
              me.isovalue = v.cast<float>();
          },
          "The isovalue the mesh was extracted at (set by extract; None otherwise; assignable): "
          "what curvature(estimator='volume') reads")
      .def("__repr__", [](const PyMesh& me) {
        return "<isocurv.Mesh " + std::to_string(me.mesh.positions.size()) + " vertices, " +
               std::to_string(me.mesh.triangles.size()) + " triangles>";
      });

  m.def(
      "load",
      [](const std::string& path, py::object spacing, py::object origin, py::object inside,
         std::string grid, py::object dims, std::string type, py::object endian) {
        volume::LoadOptions lo;
        lo.grid = grid;
        if (!spacing.is_none()) lo.spacing = triple(spacing, "spacing");
        if (!origin.is_none()) lo.origin = triple(origin, "origin");
        if (!inside.is_none()) lo.inside = inside_of(inside.cast<std::string>());
        if (!dims.is_none()) {
          const auto d = triple(dims, "dims");
          lo.raw.dims = {int(d[0]), int(d[1]), int(d[2])};
        }
        lo.raw.type = type;
        if (!endian.is_none()) {
          const std::string e = endian.cast<std::string>();
          if (e != "little" && e != "big")
            throw py::value_error("endian: expected 'little' or 'big'");
          lo.raw.big_endian = e == "big";
        }
        py::gil_scoped_release release;
        return volume::load(path, lo);
      },
      py::arg("path"), py::kw_only(), py::arg("spacing") = py::none(),
      py::arg("origin") = py::none(), py::arg("inside") = py::none(), py::arg("grid") = "",
      py::arg("dims") = py::none(), py::arg("type") = "", py::arg("endian") = py::none(),
      "Loads a volume file (.vdb .nrrd/.nhdr .mhd/.mha .nii/.nii.gz .vti .vtk .vol .raw), as the "
      "command line "
      "does. spacing/origin (x, y, z) replace the file's; inside='above'|'below' overrides which "
      "side is the "
      "object; grid names a .vdb grid; dims (x, y, z), type ('uint8' 'int16' 'uint16' 'int32' "
      "'float' "
      "'double'...) and endian ('little'|'big') describe a raw file. Raises isocurv.Error for a "
      "bad file.");

  m.def(
      "from_array", &from_array, py::arg("array"),
      py::arg("spacing") = py::make_tuple(1.0, 1.0, 1.0),
      py::arg("origin") = py::make_tuple(0.0, 0.0, 0.0), py::arg("inside") = "above",
      "A volume from a C-contiguous 3-D numpy array indexed [z, y, x] (x fastest, as files store "
      "voxels) "
      "of uint8, int8, uint16, int16, uint32, int32, float32 or float64. spacing: world units per "
      "voxel "
      "along x, y, z; origin: world position of array[0, 0, 0]; inside: 'above' (densities, CT) or "
      "'below' (signed distances). The values are copied. TypeError for another dtype, ValueError "
      "for "
      "another shape or a non-contiguous array.");

  m.def(
      "extract",
      [](const volume::Volume& v, py::object iso, bool cap, float snap, py::object device) {
        if (!(snap >= 0 && snap <= 0.5f))
          throw py::value_error("snap: expected 0..0.5 (a fraction of a voxel)");
        const DeviceChoice dc = device_choice(device);
        const float value = iso.is_none() ? float(v.stats.suggested_isovalue) : iso.cast<float>();
        if (!std::isfinite(value)) throw py::value_error("iso: must be a finite number");
        auto out = std::make_shared<PyMesh>();
        mc::Options mo;
        mo.cap = cap;
        mo.snap = snap;
        py::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(device_lock);
        out->mesh = dc.reference ? mc::extract_reference(v, value, mo)
                                 : mc::extract(v, value, opened_device(dc), mo);
        out->isovalue = value;
        return out;
      },
      py::arg("volume"), py::arg("iso") = py::none(), py::kw_only(), py::arg("cap") = false,
      py::arg("snap") = mc::kDefaultSnap, py::arg("device") = py::none(),
      "The isosurface of `volume` at `iso` (default: volume.suggested_isovalue) as a Mesh: fused "
      "(every "
      "crossed voxel edge one vertex), triangles wound so normals point out of the object. "
      "cap=True closes "
      "surfaces cut by the volume's box; snap as the CLI's --snap; device: None (a GPU, else "
      "PoCL), a "
      "device number, or 'reference' (the C++ mesher). An iso that gives no surface returns an "
      "empty mesh.");

  m.def(
      "curvature", &curvature_of, py::arg("mesh"), py::arg("volume") = nullptr, py::kw_only(),
      py::arg("estimator") = py::none(), py::arg("scale") = py::none(),
      py::arg("normals") = py::none(), py::arg("iso") = py::none(),
      py::arg("ao_scale") = py::none(), py::arg("cap") = false, py::arg("device") = py::none(),
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
lengths). Normals point out of the object, so a solid sphere of radius R has k1 = k2 = H = +1/R.
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

  m.def(
      "read_mesh",
      [](const std::string& path) {
        io::MeshFile f;
        {
          py::gil_scoped_release release;
          f = io::read_mesh(path);
        }
        auto out = std::make_shared<PyMesh>();
        out->mesh = std::move(f.mesh);
        py::object arrays = f.field ? field_dict(std::move(*f.field)) : py::dict();
        return py::make_tuple(out, arrays);
      },
      py::arg("path"),
      "Reads a mesh file (.vtp .ply .obj .stl); returns (Mesh, dict of the curvature arrays it "
      "carries, by "
      "name; empty when none). Raises isocurv.Error for a missing or malformed file.");

  m.def(
      "write_mesh",
      [](const std::string& path, const std::shared_ptr<PyMesh>& mesh, py::object arrays,
         const std::string& compress) {
        const io::Compression c = io::parse_compression(compress);
        std::optional<curvature::CurvatureField> field;
        if (!arrays.is_none()) {
          if (!py::isinstance<py::dict>(arrays))
            throw py::type_error("arrays: expected a dict of numpy arrays");
          field = field_from_dict(arrays.cast<py::dict>(), mesh->mesh.positions.size());
        }
        py::gil_scoped_release release;
        io::write_mesh(path, mesh->mesh, field ? &*field : nullptr, c);
      },
      py::arg("path"), py::arg("mesh"), py::arg("arrays") = py::none(), py::kw_only(),
      py::arg("compress") = "lz4:1",
      "Writes `mesh` and the named arrays (a dict as curvature() returns; any subset) to `path`, "
      "the format "
      "by extension (.vtp .ply .obj .stl; .obj and .stl keep only the geometry and Normals), "
      "atomically. "
      "compress: 'none', 'lz4[:LEVEL]' or 'zlib[:LEVEL]' for .vtp.");

  m.def(
      "check",
      [](const std::shared_ptr<PyMesh>& mesh) {
        mc::MeshCheck c;
        {
          py::gil_scoped_release release;
          c = mc::check_mesh(mesh->mesh);
        }
        py::dict d;
        d["vertices"] = c.vertices;
        d["triangles"] = c.triangles;
        d["duplicate_vertices"] = c.duplicate_vertices;
        d["unreferenced_vertices"] = c.unreferenced_vertices;
        d["degenerate_triangles"] = c.degenerate_triangles;
        d["edges"] = c.edges;
        d["boundary_edges"] = c.boundary_edges;
        d["non_manifold_edges"] = c.non_manifold_edges;
        d["misoriented_edges"] = c.misoriented_edges;
        d["components"] = c.components;
        d["euler_characteristic"] = c.euler;
        d["area"] = c.area;
        d["watertight"] = c.watertight();
        d["oriented"] = c.oriented();
        d["genus"] = c.genus() >= 0 ? py::object(py::int_(c.genus())) : py::object(py::none());
        d["closed_signed_volume"] = c.closed_signed_volume();
        return d;
      },
      py::arg("mesh"),
      "Fusion and topology report of `mesh` (as isocurv check): counts of duplicate and "
      "unreferenced "
      "vertices, degenerate triangles, boundary, non-manifold and misoriented edges, components, "
      "Euler "
      "characteristic, area, watertight, oriented, genus (None unless closed and oriented) and the "
      "closed "
      "part's signed volume (negative: oriented inward).");
}
