// The volume area of the isocurv Python module: isocurv.Volume (to_numpy), load and from_array.
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <openvdb/tools/Dense.h>

#include "python/bind.h"
#include "python/detail/args.h"
#include "volume/from_dense.h"
#include "volume/load.h"
#include "volume/volume.h"

namespace isocurv::python {

namespace {

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

void bind_volume(py::module_& m) {
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

  m.def(
      "load",
      [](const PathArg& path_arg, py::object spacing, py::object origin, py::object inside,
         std::string grid, py::object dims, std::string type, py::object endian, py::object level,
         py::object time_point, py::object channel) {
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
        if (!level.is_none()) lo.level = level.cast<int>();
        if (!time_point.is_none()) lo.time_point = time_point.cast<int>();
        if (!channel.is_none()) lo.channel = channel.cast<int>();
        py::gil_scoped_release release;
        return volume::load(path, lo);
      },
      py::arg("path"), py::kw_only(), py::arg("spacing") = py::none(),
      py::arg("origin") = py::none(), py::arg("inside") = py::none(), py::arg("grid") = "",
      py::arg("dims") = py::none(), py::arg("type") = "", py::arg("endian") = py::none(),
      py::arg("level") = py::none(), py::arg("time_point") = py::none(), py::arg("channel") = py::none(),
      "Loads a volume file (.vdb .nrrd/.nhdr .mhd/.mha .nii/.nii.gz .vti .vtk .vol .raw) or a Zarr "
      "store folder (level, time_point, channel pick what is read of it), as the "
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

}

}  // namespace isocurv::python
