// The isocurv Python module (pybind11): the same library calls as the command line, on numpy
// arrays. Volumes and meshes are opaque objects; mesh vertices and triangles are numpy views of
// the C++ arrays (no copy), curvature arrays numpy views of the estimated field.
//
// Threading: the GIL is released while a call computes, loads or writes; calls that use the
// OpenCL device are serialised by one lock (a Device is for one thread at a time).
//
// This file makes the module, its docstring and isocurv.Error; each area's classes and functions
// are bound by bind_<area> in python/<area>.cpp (python/bind.h), the conversions they share are in
// python/detail/.
#include <pybind11/pybind11.h>

#include <exception>
#include <string>

#include "core/cl_device.h"
#include "core/error.h"
#include "core/program_cache.h"
#include "python/bind.h"
#include "python/detail/args.h"
#include "python/detail/arrays.h"

namespace py = pybind11;
using isocurv::Error;
namespace python = isocurv::python;

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
      "Errors raise isocurv.Error (a RuntimeError) with the command line's one-line message, "
      "arguments named as here; "
      "wrong\n"
      "argument types raise TypeError, wrong shapes or values ValueError, naming the argument.";
  static py::exception<Error> error_type(m, "Error", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      error_type(python::in_python_words(e.what()).c_str());
    } catch (const cl::Error& e) {  // the library words its own (core/device_call.h): a last resort
      error_type((std::string("OpenCL call ") + e.what() + " failed: " +
                  isocurv::cl_error_name(e.err()))
                     .c_str());
    }
  });
  isocurv::set_program_cache_warnings(true);
  python::add_curvature_arrays_type(m);
  python::bind_volume(m);
  python::bind_mesh(m);
  python::bind_curvature(m);
  python::bind_measure(m);
  python::bind_labels(m);
  python::bind_features(m);
  python::bind_lines(m);
  python::bind_screen(m);
}
