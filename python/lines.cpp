// The lines area of the isocurv Python module: lines (feature lines of a mesh, as polylines,
// optionally written as .vtp or .svg).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/error.h"
#include "core/framing_points.h"
#include "curvature/curvature_field.h"
#include "lines/extract.h"
#include "lines/line_files.h"
#include "lines/line_types.h"
#include "lines/options.h"
#include "lines/polylines.h"
#include "lines/reference.h"
#include "lines/visibility.h"
#include "python/bind.h"
#include "python/detail/args.h"
#include "python/detail/arrays.h"
#include "python/detail/camera.h"
#include "python/detail/estimate.h"

namespace isocurv::python {

namespace {

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

}  // namespace

void bind_lines(py::module_& m) {
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
}

}  // namespace isocurv::python
