// The mesh area of the isocurv Python module: isocurv.Mesh, extract, read_mesh, write_mesh and
// check.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "core/error.h"
#include "curvature/curvature_field.h"
#include "io/compression.h"
#include "io/mesh_file.h"
#include "mc/extract.h"
#include "mc/extract_reference.h"
#include "mc/mesh_check.h"
#include "mc/options.h"
#include "python/bind.h"
#include "python/detail/args.h"
#include "python/detail/arrays.h"
#include "volume/isovalue_check.h"
#include "volume/volume.h"

namespace isocurv::python {

namespace {

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

/// The isovalue extract() uses on `v`: `iso`, or the suggested one for None; checked as the
/// command line checks --iso (volume::checked_isovalue), with its messages after "iso: " instead
/// of the file name: outside [min, max], or at the end of the range where no voxel can be inside
/// (a voxel equal to the isovalue is outside), is a ValueError.
float checked_isovalue(const volume::Volume& v, const py::object& iso) {
  const std::optional<float> requested =
      iso.is_none() ? std::nullopt : std::optional<float>(finite_number(iso, "iso"));
  try {
    return volume::checked_isovalue(v, requested);
  } catch (const volume::IsovalueError& e) {
    throw py::value_error(std::string("iso: ") + e.what());
  }
}

}  // namespace

void bind_mesh(py::module_& m) {
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
          // .obj and .stl hold the geometry and Normals only: say what stays behind.
          if (has_extension(path, ".obj") || has_extension(path, ".stl")) {
            std::string dropped;
            for (const auto& [key, value] : arrays.cast<py::dict>()) {
              const std::string name = py::str(key).cast<std::string>();
              if (name != "Normals") dropped += (dropped.empty() ? "" : ", ") + name;
            }
            if (!dropped.empty()) {
              const std::string ext = std::filesystem::path(path).extension().string();
              const std::string message = "write_mesh: " + ext +
                                          " keeps only the geometry and Normals; not written: " +
                                          dropped + " (use .vtp or .ply to keep them)";
              if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 1) != 0)
                throw py::error_already_set();
            }
          }
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

}  // namespace isocurv::python
