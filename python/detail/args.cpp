// The shared argument conversions of the Python module (python/detail/args.h).
#include "python/detail/args.h"

#include <cctype>
#include <utility>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <vector>

namespace isocurv::python {

std::mutex device_lock;

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

std::string type_name_of(const py::handle& o) { return Py_TYPE(o.ptr())->tp_name; }

const volume::Volume& volume_of(const VolumeArg& a, const char* arg) {
  if (!a.obj || !py::isinstance<volume::Volume>(a.obj))
    throw py::type_error(std::string(arg) +
                         ": expected an isocurv.Volume (from isocurv.load or isocurv.from_array), "
                         "not " + type_name_of(a.obj));
  return a.obj.cast<const volume::Volume&>();
}

const volume::Volume* optional_volume(const VolumeArg& a, const char* arg) {
  if (!a.obj || a.obj.is_none()) return nullptr;
  return &volume_of(a, arg);
}

std::shared_ptr<PyMesh> mesh_of(const MeshArg& a, const char* arg) {
  if (!a.obj || !py::isinstance<PyMesh>(a.obj))
    throw py::type_error(std::string(arg) +
                         ": expected an isocurv.Mesh (from isocurv.extract, isocurv.read_mesh or "
                         "isocurv.Mesh(vertices, triangles)), not " + type_name_of(a.obj));
  return a.obj.cast<std::shared_ptr<PyMesh>>();
}

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

float number_of(const py::object& o, const char* arg) {
  try {
    return o.cast<float>();
  } catch (const py::cast_error&) {
    throw py::type_error(std::string(arg) + ": expected a number");
  }
}

float finite_number(const py::object& o, const char* arg) {
  const float v = number_of(o, arg);
  if (!std::isfinite(v)) throw py::value_error(std::string(arg) + ": must be a finite number");
  return v;
}

std::string g_format(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

bool has_extension(const std::string& path, const char* ext) {
  std::string e = std::filesystem::path(path).extension().string();
  for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e == ext;
}

std::string in_python_words(const std::string& message) {
  // The flags whose library messages reach Python, and the arguments that stand for them.
  static const std::pair<const char*, const char*> kArguments[] = {
      {"compress", "compress"}, {"labels", "labels"},     {"label", "labels"},
      {"spacing", "spacing"},   {"origin", "origin"},     {"grid", "grid"},
      {"samples", "samples"},   {"lines", "lines"},       {"iso", "iso"},
      {"scale", "scale"},       {"normals", "normals"},   {"estimator", "estimator"},
      {"ao-scale", "ao_scale"}, {"dims", "dims"},         {"type", "type"},
      {"endian", "endian"},     {"inside", "inside"},     {"radius", "radius"},
      {"snap", "snap"},         {"view", "view"},         {"zoom", "zoom"},
      {"level", "level"},       {"time-point", "time_point"}, {"channel", "channel"}};
  std::string out;
  std::size_t i = 0;
  while (i < message.size()) {
    const bool starts = message.compare(i, 2, "--") == 0 &&
                        (i == 0 || !(std::isalnum(static_cast<unsigned char>(message[i - 1])) ||
                                     message[i - 1] == '-'));
    if (starts) {
      std::size_t end = i + 2;
      while (end < message.size() &&
             (std::isalnum(static_cast<unsigned char>(message[end])) || message[end] == '-'))
        ++end;
      const std::string flag = message.substr(i + 2, end - i - 2);
      const char* argument = nullptr;
      for (const auto& [f, a] : kArguments)
        if (flag == f) argument = a;
      if (argument) {
        out += argument;
        i = end;
        continue;
      }
    }
    out += message[i++];
  }
  return out;
}

}  // namespace isocurv::python
