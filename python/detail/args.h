#pragma once
// The Python module's shared argument conversions: the device choice (device=), the Mesh object,
// and arguments taken as any object so that a wrong type raises a TypeError naming the argument
// (volume=, mesh=, paths), with the small conversions every area uses (triple, finite_number).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "core/cl_device.h"
#include "core/mesh.h"
#include "volume/volume.h"

namespace isocurv::python {

namespace py = pybind11;

/// One device call at a time, across Python threads (a Device is for one thread at a time).
extern std::mutex device_lock;

/// --device as the CLI takes it: None (the default device), an index, or "reference".
struct DeviceChoice {
  bool reference = false;
  int index = -1;
};

/// device= : None, a device number or 'reference' (TypeError / ValueError naming device).
DeviceChoice device_choice(const py::object& device);

/// The OpenCL device `c` names, opened once per process (not for the reference).
Device& opened_device(const DeviceChoice& c);

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

}  // namespace isocurv::python

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
struct type_caster<isocurv::python::VolumeArg> : any_object_caster<isocurv::python::VolumeArg> {
  static constexpr auto name = const_name<isocurv::volume::Volume>();
};
template <>
struct type_caster<isocurv::python::MeshArg> : any_object_caster<isocurv::python::MeshArg> {
  static constexpr auto name = const_name<isocurv::python::PyMesh>();
};
template <>
struct type_caster<isocurv::python::VolumeOrMeshArg>
    : any_object_caster<isocurv::python::VolumeOrMeshArg> {
  static constexpr auto name = const_name<isocurv::volume::Volume>() + const_name(" | ") +
                               const_name<isocurv::python::PyMesh>();
};
template <>
struct type_caster<isocurv::python::PathArg> : any_object_caster<isocurv::python::PathArg> {
  static constexpr auto name = const_name("str | os.PathLike");
};
}  // namespace pybind11::detail

namespace isocurv::python {

/// The Python type name of `o` (for "expected ..., not <type>" messages).
std::string type_name_of(const py::handle& o);

/// The Volume `a` holds (TypeError naming `arg` otherwise).
const volume::Volume& volume_of(const VolumeArg& a, const char* arg);

/// The same, or nullptr for None.
const volume::Volume* optional_volume(const VolumeArg& a, const char* arg);

/// The Mesh `a` holds (TypeError naming `arg` otherwise).
std::shared_ptr<PyMesh> mesh_of(const MeshArg& a, const char* arg);

/// A file name from a str or an os.PathLike (pathlib.Path); TypeError naming `arg` otherwise.
std::string path_of(const PathArg& a, const char* arg);

/// inside= : 'above' or 'below' (ValueError otherwise).
volume::Inside inside_of(const std::string& s);

/// A sequence of 3 numbers (x, y, z) (TypeError / ValueError naming `name` otherwise).
std::array<double, 3> triple(const py::object& o, const char* name);

/// A Python number as a float, NaN and infinities included (TypeError naming `arg` otherwise).
float number_of(const py::object& o, const char* arg);

/// A Python number as a finite float (TypeError / ValueError naming `arg` otherwise).
float finite_number(const py::object& o, const char* arg);

/// %g of x (names of radii given as numbers, messages).
std::string g_format(double x);

/// True when `path`'s extension is `ext` (".svg"), in any case.
bool has_extension(const std::string& path, const char* ext);

/// A library message in the module's words: each command-line flag it names that the module
/// takes as an argument ("--compress", "--labels", "--label", "--spacing", ...) becomes that
/// argument's name ("compress", "labels", ...); other text is unchanged. Every isocurv.Error
/// goes through it (module.cpp).
std::string in_python_words(const std::string& message);

}  // namespace isocurv::python
