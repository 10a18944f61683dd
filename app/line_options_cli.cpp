#include "app/line_options_cli.h"

#include "core/framing_points.h"

#include <algorithm>
#include <iostream>
#include <limits>

#include "core/error.h"
#include "curvature/mesh_estimators.h"
#include "lines/extract.h"
#include "lines/reference.h"

namespace isocurv::app {

void add_line_options(CLI::App &cmd, LineCli &cli,
                      const std::string &default_list) {
  cli.list = default_list;
  auto *opt = cmd.add_option("--lines", cli.list,
                             "Feature lines, a comma list of contours "
                             "(occluding contours), suggestive "
                             "(suggestive contours), ridges, valleys, or all")
                  ->group("Lines");
  if (!default_list.empty())
    opt->capture_default_str();
  cmd.add_option("--suggestive-threshold", cli.options.suggestive_threshold,
                 "Suggestive contours: drop those whose derivative test is "
                 "under this times m^2 (m: the "
                 "median of max(|k1|,|k2|)); 0 keeps them all")
      ->check(CLI::Range(0.0, 1e6))
      ->capture_default_str()
      ->group("Lines");
  cmd.add_option("--suggestive-angle", cli.options.suggestive_angle_deg,
                 "Suggestive contours: only where the view is at least this "
                 "many degrees from the normal")
      ->check(CLI::Range(0.0, 89.9))
      ->capture_default_str()
      ->group("Lines");
  cmd.add_option("--line-smoothing", cli.options.smoothing_steps,
                 "Suggestive contours: passes of 1-ring averaging of the "
                 "radial curvature and its derivative "
                 "(removes the marching-cubes ripples; 0: none)")
      ->check(CLI::Range(0, 100))
      ->capture_default_str()
      ->group("Lines");
  cmd.add_option("--ridge-threshold", cli.options.ridge_threshold,
                 "Ridges and valleys: only where |k| exceeds this times m")
      ->check(CLI::Range(0.0, 1e6))
      ->capture_default_str()
      ->group("Lines");
}

lines::Options line_options(const LineCli &cli) {
  lines::Options o = cli.options;
  o.lines = cli.list.empty() ? lines::LineSelection{}
                             : lines::parse_line_selection(cli.list);
  return o;
}

void require_lines_supported(const lines::LineSelection &lines, const CommonOptions &o) {
  if (!lines.needs_dcurv() || o.estimator.empty())
    return;  // the defaults (volume, rusinkiewicz) give everything the lines read
  const auto m = curvature::mesh_estimator_from_name(o.estimator);
  if (!m)
    return;
  const curvature::MeshEstimatorInfo &info = curvature::mesh_estimator_info(*m);
  if (info.directions && info.derivative)
    return;
  std::string able;
  for (const curvature::MeshEstimatorInfo &e : curvature::mesh_estimators())
    if (e.directions && e.derivative)
      able += std::string(e.name) + ", ";
  lines::LineSelection asked = lines;
  asked.contours = false;
  throw Error("--lines " + asked.to_string() + " needs principal directions and the curvature "
              "derivative, which the " + info.name + " estimator does not give; with it only "
              "--lines contours works (or choose " + able + "volume)");
}

Camera picture_camera(const Mesh &mesh, const ViewSpec &view, int width,
                      int height) {
  return fit_camera_to_points(framing_points(mesh), view, double(width) / double(height));
}

lines::Segments extract_lines(const Mesh &mesh,
                              const curvature::CurvatureField &field,
                              const Camera &camera,
                              const lines::Options &options,
                              const CommonOptions &o, StageTimer &timer) {
  timer.start("lines");
  lines::Segments segs =
      reference_device(o)
          ? lines::extract_reference(mesh, field, camera, options)
          : lines::extract(mesh, field, camera, options, device_for(o));
  timer.stop();
  return segs;
}

void ensure_curvature(Surface &s, const std::string &path,
                      const CommonOptions &o, StageTimer &timer) {
  const std::size_t nv = s.mesh.positions.size();
  const bool complete =
      s.field && s.field->k1.size() == nv && s.field->dir1.size() == nv &&
      s.field->normals.size() == nv && s.field->dcurv.size() == nv;
  if (!o.flip && complete)
    return;
  const bool had_some = s.field.has_value();
  prepare_mesh_for_curvature(s, path, o);
  s.field = estimate_curvature(s.mesh, s.volume ? &*s.volume : nullptr, s.isovalue, o, timer,
                               &s.normals, &s.estimator);
  if (!s.volume && !o.quiet)
    std::cerr << "isocurv: note: " << path
              << (had_some ? " lacks some curvature arrays the lines need"
                           : " has no curvature arrays")
              << "; estimated them (" << s.estimator.estimator << " estimator, "
              << s.normals.source << " normals)\n";
}

} // namespace isocurv::app
