// The screen area of the isocurv Python module: screen (screen-space curvature per pixel of a
// ray-cast volume or a rasterised mesh).
#include <array>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/framing_points.h"
#include "core/mesh_measures.h"
#include "python/bind.h"
#include "python/detail/args.h"
#include "python/detail/arrays.h"
#include "python/detail/camera.h"
#include "screen/estimate.h"
#include "screen/gbuffer.h"
#include "screen/image_files.h"
#include "screen/rasterise.h"
#include "screen/ray_cast.h"
#include "volume/dense_field.h"
#include "volume/volume.h"

namespace isocurv::python {

namespace {

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

}  // namespace

void bind_screen(py::module_& m) {
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
}

}  // namespace isocurv::python
