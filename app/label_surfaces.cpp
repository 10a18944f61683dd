#include "app/label_surfaces.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/batch.h"
#include "core/error.h"
#include "labels/label_map.h"
#include "labels/label_surfaces.h"
#include "volume/load.h"

namespace isocurv::app {
namespace {

/// The indicator's margin (labels::scale_margin) for the binary scale or --scale's largest value.
int label_indicator_margin(const volume::Volume& v, const CommonOptions& o) {
  std::vector<double> scales;
  for (const std::string& scale : parse_scales(o.scale))
    if (scale != "auto") scales.push_back(std::stod(scale));
  return labels::scale_margin(v, scales);
}

}  // namespace

void add_label_options(CLI::App& cmd, CommonOptions& o, bool with_split) {
  cmd.add_flag("--labels", o.labels,
               "The volume is a label map (an integer segmentation): one surface per label, at the "
               "half level of its indicator, with a Label array on points and cells");
  // Checked while parsing: a bad or empty list is a usage error (exit 2), never silently none.
  cmd.add_option("--label", o.label_list, "Only these labels, e.g. 3,7 (implies --labels)")
      ->check(CLI::Validator(
          [](std::string& text) {
            try {
              labels::parse_label_list(text);
            } catch (const Error& e) {
              const std::string what = e.what(), prefix = "--label: ";
              return what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what;
            }
            return std::string();
          },
          "LIST"));
  if (with_split)
    cmd.add_flag("--split", o.split,
                 "With --labels: -o is a folder that gets one mesh file per label (label_<value>.vtp)");
}

PickedLabels pick_labels(const std::string& path, const CommonOptions& o, StageTimer& timer) {
  if (is_mesh_path(path))
    throw Error(path, "--labels needs a volume (a label map), and this is a mesh file");
  if (o.iso)
    throw Error(path, "--iso does not apply with --labels: each label's surface is at the half "
                      "level of its own indicator");
  const std::vector<std::int64_t> wanted =
      o.label_list.empty() ? std::vector<std::int64_t>{} : labels::parse_label_list(o.label_list);
  timer.start("load");
  PickedLabels p{volume::load(path, to_load_options(o.volume)), {}};
  timer.start("labels");
  const std::vector<labels::Label> all = labels::label_map_labels(p.map);
  std::vector<std::int64_t> missing;
  p.picked = labels::pick_labels(all, wanted, missing);
  timer.stop();
  if (!missing.empty() && !p.picked.empty() && !o.quiet)
    std::fprintf(stderr, "isocurv: warning: %s: %s\n", path.c_str(),
                 labels::missing_labels_note(missing).c_str());
  if (p.picked.empty())
    throw Error(path, all.empty() ? std::string("--labels: the volume holds no label (every voxel is 0)")
                                  : "--label: none of the labels given is in the volume (it holds " +
                                        std::to_string(all.size()) + " labels, from " +
                                        std::to_string(all.front().value) + " to " +
                                        std::to_string(all.back().value) + ")");
  if (!reference_device(o)) device_for(o);  // open the device (and fail on it) before timing
  return p;
}

void report_label_visits(const std::string& path, const std::vector<std::int64_t>& empty,
                         bool any, const CommonOptions& o) {
  if (!empty.empty() && !o.quiet)
    std::fprintf(stderr, "isocurv: warning: %s: %s\n", path.c_str(),
                 labels::filling_labels_note(empty).c_str());
  if (!any) throw Error(path, "--labels: no label has a surface");
}

labels::LabelSurfaceSteps label_steps(const volume::Volume& map, const CommonOptions& o,
                                      StageTimer& timer) {
  labels::LabelSurfaceSteps steps;
  steps.margin = label_indicator_margin(map, o);
  steps.extract = [&o](const volume::Volume& indicator, float isovalue) {
    return extract_surface(indicator, isovalue, o);
  };
  steps.stage = [&timer](const std::string& stage) {
    if (stage.empty()) timer.stop();
    else timer.start(stage);
  };
  return steps;
}

Surface load_label_surfaces(const std::string& path, const CommonOptions& o, StageTimer& timer,
                            bool curvature, const LabelHooks& hooks) {
  PickedLabels picked_labels = pick_labels(path, o, timer);
  const std::vector<labels::Label>& picked = picked_labels.picked;
  Surface s;
  s.volume = std::move(picked_labels.map);
  s.isovalue = labels::kIndicatorIsovalue;
  labels::LabelSurfaceSteps steps = label_steps(*s.volume, o, timer);
  if (hooks.margin) steps.margin = std::max(steps.margin, hooks.margin(*s.volume));
  if (curvature)
    steps.curvature = [&](const Mesh& mesh, const volume::Volume& indicator, float isovalue) {
      NormalsUsed used;
      curvature::EstimatorReport report;
      curvature::CurvatureField field =
          estimate_curvature(mesh, &indicator, isovalue, o, timer, &used, &report);
      s.normals.opposed += used.opposed;
      s.normals.weak += used.weak;
      s.normals.caps += used.caps;
      s.normals.source = used.source;
      if (s.estimator.estimator.empty()) s.estimator = report;
      if (hooks.field) hooks.field(mesh, indicator, field);
      return field;
    };
  labels::LabelSurfaces made = labels::label_surfaces(*s.volume, picked, steps);
  labels::LabelledMesh& merged = made.merged;
  const std::vector<std::int64_t>& empty = made.empty;
  report_label_visits(path, empty, !merged.parts.empty(), o);
  s.mesh = std::move(merged.mesh);
  s.field = std::move(merged.field);
  s.label_cells = {io::CellArray{"Label", std::move(merged.triangle_labels)}};
  s.label_parts = std::move(merged.parts);
  return s;
}


std::vector<std::string> write_split_labels(const Surface& s, const std::string& dir,
                                            const std::string& format,
                                            const CommonOptions& o, const io::Metadata& context,
                                            AtomicFileSet& outputs) {
  std::vector<std::string> paths;
  const curvature::CurvatureField none;
  for (const labels::LabelPart& p : s.label_parts) {
    Mesh mesh;
    curvature::CurvatureField field;
    labels::extract_label(s.mesh, s.field ? *s.field : none, p, mesh, field);
    const std::string path =
        (std::filesystem::path(dir) / ("label_" + std::to_string(p.value) + "." + format)).string();
    const io::CellArrays cells = {io::CellArray{"Label", std::vector<std::int32_t>(mesh.triangles.size(),
                                                                                   static_cast<std::int32_t>(p.value))}};
    outputs.write(path, [&](const std::string& tmp) {
      io::write_mesh(tmp, mesh, &field, o.compress, &context, &cells);
    });
    paths.push_back(path);
  }
  return paths;
}

void print_label_summary(const nlohmann::json& r, const std::string& what) {
  const std::size_t n = r.contains("labels") ? r["labels"].size() : 0;
  if (r.contains("outputs"))
    std::printf("wrote %zu mesh files (one per label)%s: %s ... %s\n", r["outputs"].size(), what.c_str(),
                r["outputs"].front().get<std::string>().c_str(), r["outputs"].back().get<std::string>().c_str());
  else
    std::printf("wrote %s (%s): %zu label%s, %s vertices%s, %s triangles\n",
                r["output"].get<std::string>().c_str(), format_bytes(r["output_bytes"]).c_str(), n,
                n == 1 ? "" : "s", r["vertices"].dump().c_str(), what.c_str(), r["triangles"].dump().c_str());
}

nlohmann::json label_surfaces_to_files(const std::string& in, const std::string& out,
                                       const CommonOptions& o, bool curvature) {
  require_label_output(out, o);  // before any work
  StageTimer timer;
  const Surface s = load_label_surfaces(in, o, timer, curvature);
  nlohmann::json r = surface_report(s);
  r.update(write_label_output(s, in, out, o, timer));
  r["input"] = in;
  r["compression"] = io::to_string(o.compress);
  r["programs"] = program_report();
  r["device"] = device_name(o);
  r["timings_ms"] = timer.json();
  return r;
}

void require_label_output(const std::string& out, const CommonOptions& o) {
  if (o.split) require_folder_name(out, "--split output folder");
  else require_writable_file(out);
}

nlohmann::json write_label_output(const Surface& s, const std::string& in, const std::string& out,
                                  const CommonOptions& o, StageTimer& timer) {
  timer.start("write");
  const io::Metadata context = context_metadata(s, in);
  nlohmann::json r;
  if (o.split) {
    make_output_folder(out, "--split output folder");
    AtomicFileSet outputs;
    r["outputs"] = write_split_labels(s, out, "vtp", o, context, outputs);
    outputs.commit();
  } else {
    io::write_mesh(out, s.mesh, s.field ? &*s.field : nullptr, o.compress, &context, &s.label_cells);
    r["output"] = out;
    r["output_bytes"] = file_bytes(out);
  }
  timer.stop();
  return r;
}

}  // namespace isocurv::app
