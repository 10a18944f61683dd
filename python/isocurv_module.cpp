// The isocurv Python module (pybind11): the same library calls as the command line, on numpy
// arrays. Volumes and meshes are opaque objects; mesh vertices and triangles are numpy views of
// the C++ arrays (no copy), curvature arrays numpy views of the estimated field.
//
// Threading: the GIL is released while a call computes, loads or writes; calls that use the
// OpenCL device are serialised by one lock (a Device is for one thread at a time).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include <openvdb/tools/Dense.h>

#include <filesystem>

#include "core/camera.h"
#include "core/cl_device.h"
#include "core/error.h"
#include "core/mesh.h"
#include "core/mesh_measures.h"
#include "core/framing_points.h"
#include "core/program_cache.h"
#include "curvature/ao_scale.h"
#include "curvature/curvature_field.h"
#include "curvature/estimate.h"
#include "curvature/estimator.h"
#include "curvature/face_average_normals.h"
#include "curvature/reference.h"
#include "curvature/topology.h"
#include "features/features.h"
#include "io/compression.h"
#include "io/field_arrays.h"
#include "io/mesh_file.h"
#include "measure/object_measures.h"
#include "labels/label_map.h"
#include "curvature/auto_scale.h"
#include "curvature/field_stats.h"
#include "lines/extract.h"
#include "lines/line_files.h"
#include "lines/line_types.h"
#include "lines/options.h"
#include "lines/polylines.h"
#include "lines/reference.h"
#include "lines/visibility.h"
#include "mc/extract.h"
#include "mc/extract_reference.h"
#include "mc/mesh_check.h"
#include "mc/options.h"
#include "screen/estimate.h"
#include "screen/gbuffer.h"
#include "screen/image_files.h"
#include "screen/rasterise.h"
#include "screen/ray_cast.h"
#include "volume/dense_field.h"
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

// Arguments taken as any object and checked by the function, so that a wrong type raises a
// TypeError naming the argument ("volume: expected an isocurv.Volume ..., not str") instead of
// pybind11's list of signatures; the signatures still show the type (the casters below).
struct VolumeArg {
  py::object obj;
};
struct MeshArg {
  py::object obj;
};
struct VolumeOrMeshArg {
  py::object obj;
};
struct PathArg {  ///< a file name: a str or an os.PathLike (pathlib.Path)
  py::object obj;
};

}  // namespace

namespace pybind11::detail {
template <class T>
struct any_object_caster {
  bool load(handle src, bool) {
    value.obj = reinterpret_borrow<object>(src);
    return true;
  }
  T value;
  operator T*() { return &value; }
  operator T&() { return value; }
  template <typename U>
  using cast_op_type = movable_cast_op_type<U>;
};
template <>
struct type_caster<VolumeArg> : any_object_caster<VolumeArg> {
  static constexpr auto name = const_name<volume::Volume>();
};
template <>
struct type_caster<MeshArg> : any_object_caster<MeshArg> {
  static constexpr auto name = const_name<PyMesh>();
};
template <>
struct type_caster<VolumeOrMeshArg> : any_object_caster<VolumeOrMeshArg> {
  static constexpr auto name = const_name<volume::Volume>() + const_name(" | ") + const_name<PyMesh>();
};
template <>
struct type_caster<PathArg> : any_object_caster<PathArg> {
  static constexpr auto name = const_name("str | os.PathLike");
};
}  // namespace pybind11::detail

namespace {

std::string type_name_of(const py::handle& o) { return Py_TYPE(o.ptr())->tp_name; }

/// The Volume `a` holds (TypeError naming `arg` otherwise).
const volume::Volume& volume_of(const VolumeArg& a, const char* arg) {
  if (!a.obj || !py::isinstance<volume::Volume>(a.obj))
    throw py::type_error(std::string(arg) +
                         ": expected an isocurv.Volume (from isocurv.load or isocurv.from_array), "
                         "not " + type_name_of(a.obj));
  return a.obj.cast<const volume::Volume&>();
}

/// The same, or nullptr for None.
const volume::Volume* optional_volume(const VolumeArg& a, const char* arg) {
  if (!a.obj || a.obj.is_none()) return nullptr;
  return &volume_of(a, arg);
}

/// The Mesh `a` holds (TypeError naming `arg` otherwise).
std::shared_ptr<PyMesh> mesh_of(const MeshArg& a, const char* arg) {
  if (!a.obj || !py::isinstance<PyMesh>(a.obj))
    throw py::type_error(std::string(arg) +
                         ": expected an isocurv.Mesh (from isocurv.extract, isocurv.read_mesh or "
                         "isocurv.Mesh(vertices, triangles)), not " + type_name_of(a.obj));
  return a.obj.cast<std::shared_ptr<PyMesh>>();
}

/// A file name from a str or an os.PathLike (pathlib.Path); TypeError naming `arg` otherwise.
std::string path_of(const PathArg& a, const char* arg) {
  if (a.obj && py::isinstance<py::str>(a.obj)) return a.obj.cast<std::string>();
  py::object os = py::module_::import("os");
  if (a.obj && !a.obj.is_none() && py::hasattr(a.obj, "__fspath__")) {
    py::object s = os.attr("fsdecode")(os.attr("fspath")(a.obj));
    return s.cast<std::string>();
  }
  throw py::type_error(std::string(arg) + ": expected a file name (a str or a pathlib.Path), not " +
                       type_name_of(a.obj));
}

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

/// A CurvatureArrays of the field's arrays carrying `report`.
py::object curvature_arrays(curvature::CurvatureField&& field, py::dict report) {
  py::object out = field_dict(std::move(field), curvature_arrays_type());
  out.attr("report") = report;
  return out;
}

/// A ValueError unless `mesh` lies in `volume`: its bounding box (finite vertices) within the
/// volume's world bounds (the domain's corners through the transform) grown by one voxel (the
/// longest voxel edge). A mesh of another volume, or of this one loaded with another spacing or
/// origin, would otherwise be measured in the volume's outside: wrong curvature, no error.
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

/// A curvature estimate and what it used (CurvatureArrays.report).
struct Estimated {
  curvature::CurvatureField field;
  py::dict report;
};

/// curvature()'s estimate (the CLI's rules), also what features() and lines() estimate when
/// given no curvature arrays.
Estimated estimate_of(const std::shared_ptr<PyMesh>& mesh, const volume::Volume* volume,
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
  if (volume) check_mesh_in_volume(mesh->mesh, *volume);
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
  return {std::move(field), report_dict(report, source, source == "volume" ? &vn : nullptr)};
}

py::object curvature_of(const MeshArg& mesh_arg, const VolumeArg& volume_arg, py::object estimator,
                        py::object scale, py::object normals_arg, py::object iso,
                        py::object ao_scale, bool cap, py::object device) {
  const std::shared_ptr<PyMesh> mesh = mesh_of(mesh_arg, "mesh");
  const volume::Volume* volume = optional_volume(volume_arg, "volume");
  Estimated e = estimate_of(mesh, volume, estimator, scale, normals_arg, iso, ao_scale, cap, device);
  return curvature_arrays(std::move(e.field), e.report);
}

/// The isovalue extract() uses on `v`: `iso`, or the suggested one for None; checked as the
/// command line's checked_isovalue (app/pipeline.cpp) checks --iso, with its messages after
/// "iso: " instead of the file name: outside [min, max], or at the end of the range where no
/// voxel can be inside (a voxel equal to the isovalue is outside), is a ValueError.
float checked_isovalue(const volume::Volume& v, const py::object& iso) {
  const float value =
      iso.is_none() ? float(v.stats.suggested_isovalue) : finite_number(iso, "iso");
  if (!std::isfinite(value)) throw py::value_error("iso: isovalue must be a finite number");
  auto num = [](double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", x);
    return std::string(buf);
  };
  const std::string range = "[" + num(v.stats.min) + ", " + num(v.stats.max) + "]";
  if (!iso.is_none() && (value < v.stats.min || value > v.stats.max))
    throw py::value_error("iso: isovalue " + num(value) + " is outside the value range " + range);
  const bool above = v.inside == volume::Inside::Above;
  if (value == float(above ? v.stats.max : v.stats.min))
    throw py::value_error("iso: isovalue " + num(value) + " equals the " +
                          (above ? "maximum" : "minimum") +
                          " value, so there is no surface: a voxel equal to the isovalue counts "
                          "as outside, and none is " + (above ? "above" : "below") +
                          " it (the range is " + range + ")");
  return value;
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
    // The library's one rule for unmeasured vertices, as estimate_field applies it.
    r.implausible = curvature::flag_implausible(t.frame, field);
    r.unreliable += r.implausible;
  }
  return curvature_arrays(std::move(field), report_dict(r, source, nullptr));
}

/// A copy of `v` as a numpy array of `shape`.
template <class T>
py::array copy_array(const std::vector<T>& v, std::vector<py::ssize_t> shape) {
  py::array_t<T> a(shape);
  if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(T));
  return std::move(a);
}

/// %g of x (names of radii given as numbers, messages).
std::string g_format(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

/// The isovalue of `mesh` for the volume stages: iso= when given, else mesh.isovalue (set by
/// extract); a ValueError naming `why` when neither.
float mesh_isovalue(const PyMesh& mesh, const py::object& iso, const std::string& why) {
  if (!iso.is_none()) return finite_number(iso, "iso");
  if (mesh.isovalue) return *mesh.isovalue;
  throw py::value_error("iso: " + why +
                        " needs the mesh's isovalue (meshes from isocurv.extract carry it as "
                        "mesh.isovalue; else pass iso=)");
}

/// The curvature field the features and lines read: `arrays` (a dict as curvature() returns)
/// checked to carry `needed`, or, for None, curvature(mesh, volume, iso=iso) with its defaults.
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

/// measure() and measure_labels()'s dict: one numpy array per measure, one entry per object.
struct MeasureColumns {
  std::vector<double> area, mesh_area, volume, int_h, int_k, gap, box, scale;
  std::vector<std::int64_t> euler, genus, vertices, triangles, unmeasured;
  std::vector<std::uint8_t> closed, resolved;

  void add(const measure::ObjectMeasures& m) {
    area.push_back(m.area);
    mesh_area.push_back(m.mesh_area);
    scale.push_back(m.scale);
    resolved.push_back(m.resolved ? 1 : 0);
    volume.push_back(m.closed ? m.volume : std::numeric_limits<double>::quiet_NaN());
    int_h.push_back(m.integral_H);
    int_k.push_back(m.integral_K);
    gap.push_back(m.gauss_bonnet_gap());
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
  std::vector<std::int64_t> wanted;
  auto add = [&](const py::handle& item) {
    if (py::isinstance<py::bool_>(item) || !py::isinstance<py::int_>(item))
      throw py::type_error("labels: expected int labels, not " + type_name_of(item));
    const std::int64_t value = item.cast<std::int64_t>();
    if (std::find(wanted.begin(), wanted.end(), value) != wanted.end())
      throw py::value_error("labels: label " + std::to_string(value) + " is given twice");
    wanted.push_back(value);
  };
  if (labels_arg.is_none()) {
  } else if (py::isinstance<py::int_>(labels_arg) && !py::isinstance<py::bool_>(labels_arg)) {
    add(labels_arg);
  } else if (py::isinstance<py::sequence>(labels_arg) && !py::isinstance<py::str>(labels_arg)) {
    for (const py::handle item : labels_arg.cast<py::sequence>()) add(item);
    if (wanted.empty()) throw py::value_error("labels: empty; pass None for every label");
  } else {
    throw py::type_error("labels: expected None, an int or a sequence of ints, not " + type_name_of(labels_arg));
  }
  const std::vector<labels::Label> all = labels::label_map_labels(v);
  std::vector<std::int64_t> missing;
  const std::vector<labels::Label> picked = labels::pick_labels(all, wanted, missing);
  if (picked.empty()) throw py::value_error("labels: none of the labels given is in the volume");
  if (!missing.empty()) {
    std::string list;
    for (std::int64_t m : missing) list += (list.empty() ? "" : ", ") + std::to_string(m);
    PyErr_WarnEx(PyExc_UserWarning, ("no voxel holds label " + list + "; left out").c_str(), 1);
  }
  const DeviceChoice dc = device_choice(device);
  const int margin = labels::indicator_margin(curvature::kBinaryScaleVoxels);
  std::vector<std::int64_t> label, components;
  MeasureColumns columns;
  for (const labels::Label& l : picked) {
    const volume::Volume ind = labels::label_indicator(v, l, margin);
    auto mesh = std::make_shared<PyMesh>();
    {
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(device_lock);
      mesh->mesh = dc.reference ? mc::extract_reference(ind, 0.5f, mc::Options{})
                                : mc::extract(ind, 0.5f, opened_device(dc), mc::Options{});
    }
    mesh->isovalue = 0.5f;
    if (mesh->mesh.triangles.empty()) continue;  // the label fills the box: no surface
    const curvature::CurvatureField field =
        estimate_of(mesh, &ind, py::none(), py::none(), py::none(), py::float_(0.5), py::none(), false, device).field;
    const std::vector<measure::ObjectMeasures> objects = measure::object_measures(mesh->mesh, field);
    label.push_back(l.value);
    components.push_back(std::int64_t(objects.size()));
    columns.add(measure::total(objects));
    long long genus = 0;  // the sum of its components' genera (-1 when one is cut)
    for (const auto& m : objects) genus = (genus < 0 || !m.closed) ? -1 : genus + m.genus();
    columns.genus.back() = genus;
  }
  const py::ssize_t n = py::ssize_t(label.size());
  py::dict out = columns.dict();
  out["label"] = copy_array(label, {n});
  out["components"] = copy_array(components, {n});
  return out;
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

/// The camera keywords (the CLI's --view --azimuth --elevation --zoom --ortho) as a ViewSpec.
ViewSpec view_of(const std::string& view, double azimuth, double elevation, double zoom,
                 bool ortho) {
  ViewSpec spec;
  try {
    spec.view = parse_named_view(view);
  } catch (const Error& e) {
    throw py::value_error(std::string("view: ") + e.what());
  }
  if (!(azimuth >= -360 && azimuth <= 360))
    throw py::value_error("azimuth: expected -360..360 degrees");
  if (!(elevation >= -90 && elevation <= 90))
    throw py::value_error("elevation: expected -90..90 degrees");
  if (!(zoom >= 0.05 && zoom <= 50)) throw py::value_error("zoom: expected 0.05..50");
  spec.azimuth_deg = azimuth, spec.elevation_deg = elevation, spec.zoom = zoom, spec.ortho = ortho;
  return spec;
}

/// size=(width, height) as the CLI's --size WIDTHxHEIGHT, each 16..8192.
std::array<int, 2> size_of(const py::object& size) {
  std::array<int, 2> wh{};
  try {
    const auto v = size.cast<std::vector<long>>();
    if (v.size() != 2) throw py::cast_error();
    wh = {int(std::clamp<long>(v[0], -1, 1 << 20)), int(std::clamp<long>(v[1], -1, 1 << 20))};
  } catch (const py::cast_error&) {
    throw py::type_error("size: expected (width, height), two ints");
  }
  if (wh[0] < 16 || wh[1] < 16 || wh[0] > screen::kMaxImageSide || wh[1] > screen::kMaxImageSide)
    throw py::value_error("size: expected (width, height), each 16..8192");
  return wh;
}

py::dict camera_dict(const Camera& c) {
  py::dict d;
  d["position"] = py::make_tuple(c.position[0], c.position[1], c.position[2]);
  d["focal_point"] = py::make_tuple(c.focal_point[0], c.focal_point[1], c.focal_point[2]);
  d["view_up"] = py::make_tuple(c.view_up[0], c.view_up[1], c.view_up[2]);
  d["ortho"] = c.ortho;
  d["view_angle"] = c.view_angle_deg;
  d["parallel_scale"] = c.parallel_scale;
  return d;
}

bool has_extension(const std::string& path, const char* ext) {
  std::string e = std::filesystem::path(path).extension().string();
  for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e == ext;
}

py::object lines_of(const MeshArg& mesh_arg, const VolumeArg& volume_arg, const py::object& arrays,
                    const std::string& list, double suggestive_threshold, double suggestive_angle,
                    int line_smoothing, double ridge_threshold, const std::string& view,
                    double azimuth, double elevation, double zoom, bool ortho,
                    const py::object& size, const py::object& visible_arg,
                    const PathArg& output_arg, const py::object& iso, py::object device) {
  const std::shared_ptr<PyMesh> mesh = mesh_of(mesh_arg, "mesh");
  const volume::Volume* volume = optional_volume(volume_arg, "volume");
  const DeviceChoice dc = device_choice(device);
  const std::string output =
      output_arg.obj && !output_arg.obj.is_none() ? path_of(output_arg, "output") : "";
  const bool svg = !output.empty() && has_extension(output, ".svg");
  if (!output.empty() && !svg && !has_extension(output, ".vtp"))
    throw py::value_error("output: lines writes .vtp (polylines) or .svg (a drawing), not '" +
                          std::filesystem::path(output).extension().string() + "'");
  if (!visible_arg.is_none() && !py::isinstance<py::bool_>(visible_arg))
    throw py::type_error("visible: expected True, False or None, not " + type_name_of(visible_arg));
  const bool visible = visible_arg.is_none() ? svg : visible_arg.cast<bool>();
  if (svg && !visible)
    throw py::value_error("visible: an .svg drawing shows the visible lines only (as the CLI's)");
  lines::Options lo;
  try {
    lo.lines = lines::parse_line_selection(list);
  } catch (const Error& e) {
    std::string m = e.what();
    if (m.rfind("--lines: ", 0) == 0) m = m.substr(9);
    throw py::value_error("lines: " + m);
  }
  if (!(suggestive_threshold >= 0 && suggestive_threshold <= 1e6))
    throw py::value_error("suggestive_threshold: expected 0..1e6 (times m^2)");
  if (!(suggestive_angle >= 0 && suggestive_angle <= 89.9))
    throw py::value_error("suggestive_angle: expected 0..89.9 degrees");
  if (line_smoothing < 0 || line_smoothing > 100)
    throw py::value_error("line_smoothing: expected 0..100 passes");
  if (!(ridge_threshold >= 0 && ridge_threshold <= 1e6))
    throw py::value_error("ridge_threshold: expected 0..1e6 (times m)");
  lo.suggestive_threshold = suggestive_threshold;
  lo.suggestive_angle_deg = suggestive_angle;
  lo.smoothing_steps = line_smoothing;
  lo.ridge_threshold = ridge_threshold;
  const ViewSpec spec = view_of(view, azimuth, elevation, zoom, ortho);
  const std::array<int, 2> wh = size_of(size);
  if (mesh->mesh.triangles.empty()) throw py::value_error("mesh: has no triangles");
  if (volume) check_mesh_in_volume(mesh->mesh, *volume);
  if (!arrays.is_none() && !iso.is_none())
    throw py::value_error("iso: applies when the curvature is estimated here (arrays=None)");
  curvature::CurvatureField field =
      field_for(mesh, volume, arrays, iso, device, {"Normals", "k1", "k2"});
  lines::Polylines poly;
  Camera camera;
  {
    py::gil_scoped_release release;
    camera = fit_camera_to_points(framing_points(mesh->mesh), spec, double(wh[0]) / wh[1]);
    lines::Segments segs;
    {
      std::lock_guard<std::mutex> lock(device_lock);
      segs = dc.reference ? lines::extract_reference(mesh->mesh, field, camera, lo)
                          : lines::extract(mesh->mesh, field, camera, lo, opened_device(dc));
    }
    if (visible)
      segs = lines::select_segments(
          segs, lines::VisibilityTester(mesh->mesh).visible_segments(segs, camera));
    poly = lines::join_segments(segs);
    if (svg)
      lines::write_svg(output, poly, camera, wh[0], wh[1]);
    else if (!output.empty())
      lines::write_vtp(output, poly);
  }
  const std::size_t nl = poly.line_count();
  py::dict out;
  const float* pts = poly.points.empty() ? nullptr : poly.points.data()->data();
  py::array points = copy_array(std::vector<float>(pts, pts + 3 * poly.points.size()),
                                {py::ssize_t(poly.points.size()), 3});
  out["points"] = points;
  out["offsets"] = copy_array(poly.offsets, {py::ssize_t(poly.offsets.size())});
  py::list lines_list;
  for (std::size_t i = 0; i < nl; ++i)
    lines_list.append(points[py::slice(poly.offsets[i], poly.offsets[i + 1], 1)]);
  out["polylines"] = lines_list;
  std::vector<std::uint8_t> types(nl);
  for (std::size_t i = 0; i < nl; ++i) types[i] = std::uint8_t(poly.type[i]);
  out["type"] = copy_array(types, {py::ssize_t(nl)});
  out["strength"] = copy_array(poly.strength, {py::ssize_t(nl)});
  py::list type_names;
  for (int t = 0; t < lines::kLineTypeCount; ++t) type_names.append(lines::to_string(lines::LineType(t)));
  out["type_names"] = type_names;
  py::dict length;
  for (int t = 0; t < lines::kLineTypeCount; ++t)
    if (lo.lines.has(lines::LineType(t)))
      length[lines::to_string(lines::LineType(t)).c_str()] = poly.length(lines::LineType(t));
  out["length"] = length;
  out["camera"] = camera_dict(camera);
  return out;
}

/// An image of the G-buffer's layout (x + width y, y up) as a numpy [row, column] array with
/// row 0 at the top (as the PNG shows it, and as matplotlib's imshow draws it).
template <class T>
py::array image_of(const std::vector<T>& v, int width, int height) {
  py::array_t<T> a({py::ssize_t(height), py::ssize_t(width)});
  T* out = a.mutable_data();
  for (int r = 0; r < height; ++r)
    std::memcpy(out + std::size_t(r) * width, v.data() + std::size_t(height - 1 - r) * width,
                std::size_t(width) * sizeof(T));
  return std::move(a);
}

py::object screen_of(const VolumeOrMeshArg& source, const py::object& iso, const std::string& view,
                     double azimuth, double elevation, double zoom, bool ortho,
                     const py::object& size, const std::string& estimator, int edges, bool lod,
                     int lod_size, int fan, const std::string& depth, const std::string& rule,
                     double smooth, int mellado_radius, const PathArg& raw_arg,
                     py::object device) {
  const bool is_volume = source.obj && py::isinstance<volume::Volume>(source.obj);
  const bool is_mesh = source.obj && py::isinstance<PyMesh>(source.obj);
  if (!is_volume && !is_mesh)
    throw py::type_error("volume_or_mesh: expected an isocurv.Volume (ray cast) or an "
                         "isocurv.Mesh (rasterised), not " + type_name_of(source.obj));
  const DeviceChoice dc = device_choice(device);
  const std::string raw = raw_arg.obj && !raw_arg.obj.is_none() ? path_of(raw_arg, "raw") : "";
  if (!raw.empty() && !has_extension(raw, ".vti"))
    throw py::value_error("raw: writes a .vti file (VTK image data), not '" + raw + "'");
  screen::ScreenOptions so;
  if (estimator != "prantl" && estimator != "mellado")
    throw py::value_error("estimator: expected 'prantl' or 'mellado', not '" + estimator + "'");
  so.estimator =
      estimator == "mellado" ? screen::ScreenEstimator::mellado : screen::ScreenEstimator::prantl;
  if (edges != 2 && edges != 3) throw py::value_error("edges: expected 2 or 3");
  if (lod_size < 1 || lod_size > 64) throw py::value_error("lod_size: expected 1..64 pixels");
  if (fan != 4 && fan != 8) throw py::value_error("fan: expected 4 or 8");
  if (depth != "linear" && depth != "window")
    throw py::value_error("depth: expected 'linear' or 'window', not '" + depth + "'");
  if (rule != "report" && rule != "paper")
    throw py::value_error("discontinuity: expected 'report' or 'paper', not '" + rule + "'");
  if (mellado_radius < 1 || mellado_radius > 32)
    throw py::value_error("mellado_radius: expected 1..32 pixels");
  if (!(smooth >= 0 && smooth <= volume::kMaxSmoothingVoxels))
    throw py::value_error("smooth: expected 0..6 voxels");
  so.edges = edges, so.lod = lod, so.size_max = lod_size, so.fan = fan;
  so.depth = depth == "window" ? screen::DepthMapping::window : screen::DepthMapping::linear;
  so.rule = rule == "paper" ? screen::DiscontinuityRule::paper : screen::DiscontinuityRule::report;
  so.mellado_radius = mellado_radius;
  const ViewSpec spec = view_of(view, azimuth, elevation, zoom, ortho);
  const std::array<int, 2> wh = size_of(size);
  std::shared_ptr<PyMesh> mesh;
  const volume::Volume* vol = nullptr;
  float value = 0;
  if (is_mesh) {
    mesh = source.obj.cast<std::shared_ptr<PyMesh>>();
    if (!iso.is_none()) throw py::value_error("iso: applies to a volume (the ray cast) only");
    if (smooth > 0) throw py::value_error("smooth: applies to a volume (the ray cast) only");
    if (mesh->mesh.triangles.empty()) throw py::value_error("volume_or_mesh: the mesh has no triangles");
  } else {
    vol = &source.obj.cast<const volume::Volume&>();
    value = iso.is_none() ? float(vol->stats.suggested_isovalue) : finite_number(iso, "iso");
  }
  screen::GBuffer g;
  screen::ScreenCurvature c;
  Camera camera;
  bool empty = false;
  {
    py::gil_scoped_release release;
    std::optional<volume::DenseField> cast;
    const double aspect = double(wh[0]) / wh[1];
    if (vol) {
      cast.emplace(*vol);
      if (smooth > 0) cast->smooth(smooth);
      std::array<double, 6> bounds{};
      if (!cast->surface_bounds(value, bounds)) empty = true, bounds = cast->bounds;
      camera = fit_camera(bounds, spec, aspect);
    } else {
      camera = fit_camera_to_points(framing_points(mesh->mesh), spec, aspect);
    }
    const screen::ViewFrame frame = screen::view_frame(camera, wh[0], wh[1]);
    std::lock_guard<std::mutex> lock(device_lock);
    if (cast)
      g = dc.reference ? screen::ray_cast_reference(*cast, value, frame)
                       : screen::ray_cast(*cast, value, frame, opened_device(dc));
    else
      g = screen::rasterise(mesh->mesh, area_weighted_normals(mesh->mesh), frame);
    c = dc.reference ? screen::estimate_reference(g, so)
                     : screen::estimate(g, opened_device(dc), so);
    if (!raw.empty()) screen::write_raw(raw, c);
  }
  py::object out = curvature_arrays_type();
  out["H"] = image_of(c.H, c.width, c.height);
  if (so.estimator == screen::ScreenEstimator::prantl) out["K"] = image_of(c.K, c.width, c.height);
  out["Valid"] = image_of(c.valid, c.width, c.height);
  out["Step"] = image_of(c.step, c.width, c.height);
  py::dict report;
  report["producer"] = vol ? "ray cast" : "rasterised mesh";
  report["estimator"] = screen::estimator_label(so, vol ? smooth : 0);
  if (vol) report["isovalue"] = value;
  report["surface_pixels"] = g.valid_count();
  report["estimated_pixels"] = c.valid_count();
  report["empty"] = empty;
  report["camera"] = camera_dict(camera);
  out.attr("report") = report;
  return out;
}

/// Volume.to_numpy(): the data domain's voxels as a float32 array [z, y, x].
py::array volume_to_numpy(const volume::Volume& v) {
  const openvdb::CoordBBox box = v.domain;
  if (!v.grid || box.empty()) return py::array_t<float>(std::vector<py::ssize_t>{0, 0, 0});
  const openvdb::Coord d = box.dim();
  py::array_t<float> a({py::ssize_t(d.z()), py::ssize_t(d.y()), py::ssize_t(d.x())});
  float* p = a.mutable_data();
  {
    py::gil_scoped_release release;
    // LayoutXYZ: x varies fastest, the C order of an array indexed [z, y, x].
    openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> dense(box, p);
    openvdb::tools::copyToDense(*v.grid, dense);
  }
  return std::move(a);
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
      "topo.curvature(positions)\n"
      "  isocurv.features(mesh, v, radius='2%'), isocurv.lines(mesh, arrays=arrays), "
      "isocurv.screen(v)\n\n"
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
        "The dict of numpy arrays curvature(), features() and screen() return, with .report: "
        "what was used (for curvature: the estimator, its parameters and the unreliable count).";
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
      .def("to_numpy", &volume_to_numpy,
           R"doc(The voxels of the data domain as a new float32 numpy array indexed [z, y, x] (x
fastest; its shape is volume.shape), whatever the file's voxel_type: the volume holds every type
as 32-bit floats (integers are exact up to 2^24), so from_array(a).to_numpy() equals
a.astype(numpy.float32). array[0, 0, 0] is the domain's first voxel, at volume.origin for dense
files and arrays; a sparse .vdb grid gives its active box, its inactive voxels holding the grid's
background. NaN and infinite voxels of the file hold what loading replaced them with (an outside
value). A copy: writing to it does not change the volume.)doc")
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
      [](const PathArg& path_arg, py::object spacing, py::object origin, py::object inside,
         std::string grid, py::object dims, std::string type, py::object endian) {
        const std::string path = path_of(path_arg, "path");
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
      [](const VolumeArg& volume_arg, py::object iso, bool cap, float snap, py::object device) {
        const volume::Volume& v = volume_of(volume_arg, "volume");
        if (!(snap >= 0 && snap <= 0.5f))
          throw py::value_error("snap: expected 0..0.5 (a fraction of a voxel)");
        const DeviceChoice dc = device_choice(device);
        const float value = checked_isovalue(v, iso);
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
      "device number, or 'reference' (the C++ mesher). An iso outside volume.value_range, or at "
      "its inside end (the maximum for inside='above': a voxel equal to the isovalue is "
      "outside), raises ValueError with the command line's message; another iso that gives no "
      "surface returns an empty mesh.");

  m.def(
      "curvature", &curvature_of, py::arg("mesh"), py::arg("volume") = py::none(), py::kw_only(),
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
A mesh that does not lie in `volume` (its bounding box more than a voxel beyond the volume's
world bounds: a mesh of another volume, or other spacing or origin) raises ValueError.
Wrong combinations raise ValueError naming the argument.)doc");

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
kResolvedExtent times that scale, its curvature integrals unreliable). arrays: the mesh's
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
lacks are left out with a UserWarning. A float volume, or more than 65,535 labels, raises
isocurv.Error; none of `labels` in the volume raises ValueError.)doc");

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

  m.def("lines", &lines_of, py::arg("mesh"), py::arg("volume") = py::none(), py::kw_only(),
        py::arg("arrays") = py::none(), py::arg("lines") = "contours,suggestive",
        py::arg("suggestive_threshold") = 0.05, py::arg("suggestive_angle") = 10.0,
        py::arg("line_smoothing") = 4, py::arg("ridge_threshold") = 1.5, py::arg("view") = "iso",
        py::arg("azimuth") = 0.0, py::arg("elevation") = 0.0, py::arg("zoom") = 1.0,
        py::arg("ortho") = false, py::arg("size") = py::make_tuple(1024, 768),
        py::arg("visible") = py::none(), py::arg("output") = py::none(),
        py::arg("iso") = py::none(), py::arg("device") = py::none(),
        R"doc(Feature lines of `mesh` (isocurv lines; see docs/lines.md) as a dict:
'points' (p, 3) float32 and 'offsets' (L + 1,) uint32 (line i is points[offsets[i]:offsets[i+1]],
a closed loop repeating its first point), 'polylines' (those L slices, views of 'points'), 'type'
(L,) uint8 (0 contours, 1 suggestive, 2 ridges, 3 valleys: the .vtp's LineType; 'type_names'
names them), 'strength' (L,) float32 in [0, 1], 'length' {type name: world length} and 'camera'
{position, focal_point, view_up, ortho, view_angle, parallel_scale}.

lines: comma list of contours, suggestive, ridges, valleys or all (--lines); the thresholds as
--suggestive-threshold, --suggestive-angle, --line-smoothing, --ridge-threshold. The camera (the
contours depend on it) is the one isocurv render and lines use for the same view ('iso', '+x',
'-x', '+y', '-y', '+z', '-z'), azimuth, elevation, zoom, ortho and size (width, height).
visible=True keeps only the lines no triangle hides (the .svg's ray cast); default: True for an
.svg output, else False. output: a .vtp (the lines, cell arrays LineType and Strength) or .svg
drawing to write as well. arrays: the curvature (a dict as curvature() returns); None estimates
curvature(mesh, volume) with its defaults (iso= for a mesh without mesh.isovalue).)doc");

  m.def("screen", &screen_of, py::arg("volume_or_mesh"), py::kw_only(),
        py::arg("iso") = py::none(), py::arg("view") = "iso", py::arg("azimuth") = 0.0,
        py::arg("elevation") = 0.0, py::arg("zoom") = 1.0, py::arg("ortho") = false,
        py::arg("size") = py::make_tuple(1024, 768), py::arg("estimator") = "prantl",
        py::arg("edges") = 2, py::arg("lod") = false, py::arg("lod_size") = 8, py::arg("fan") = 4,
        py::arg("depth") = "linear", py::arg("discontinuity") = "report",
        py::arg("smooth") = 0.0, py::arg("mellado_radius") = 4, py::arg("raw") = py::none(),
        py::arg("device") = py::none(),
        R"doc(Screen-space curvature per pixel (isocurv screen; see docs/screen.md): a Volume's
isosurface at `iso` (default volume.suggested_isovalue) ray cast, no mesh, or a Mesh rasterised;
then Prantl's per-pixel shape operator (estimator='prantl') or Mellado's sphere fit ('mellado',
H only). Returns a CurvatureArrays of images, numpy arrays [rows, columns] = (height, width), row
0 at the top of the picture: 'H' float32, 'K' float32 (prantl only), 'Valid' uint8 (1 where
estimated; silhouettes, depth discontinuities and the background are 0 and hold H = K = 0, not
NaN) and 'Step' uint8 (the LOD step used); `.report`: {'producer', 'estimator', 'isovalue',
'surface_pixels', 'estimated_pixels', 'empty' (the isovalue gives no surface), 'camera'}.

The image is the whole size (width, height), fitted as isocurv render fits its camera (the CLI's
PNG puts a smaller image inside a title and legend). edges (2|3), lod, lod_size, fan (4|8), depth
('linear'|'window'), discontinuity ('report'|'paper'), smooth (voxels, volume only) and
mellado_radius as the CLI's --edges --lod --lod-size --fan --depth --discontinuity --smooth
--mellado-radius. raw: a .vti to write as the CLI's --raw (y up, arrays H, K, Valid).)doc");

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
      [](const PathArg& path_arg) {
        const std::string path = path_of(path_arg, "path");
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
      [](const PathArg& path_arg, const MeshArg& mesh_arg, py::object arrays,
         const std::string& compress) {
        const std::string path = path_of(path_arg, "path");
        const std::shared_ptr<PyMesh> mesh = mesh_of(mesh_arg, "mesh");
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
      [](const MeshArg& mesh_arg) {
        const std::shared_ptr<PyMesh> mesh = mesh_of(mesh_arg, "mesh");
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
