#include "app/pipeline.h"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/mesh_measures.h"
#include "core/progress.h"
#include "curvature/ao_scale.h"
#include "curvature/estimate.h"
#include "curvature/field_stats.h"
#include "curvature/weld.h"
#include "io/mesh_file.h"
#include "mc/extract.h"
#include "mc/mesh_check.h"
#include "volume/gradient_normals.h"
#include "volume/load.h"

namespace isocurv::app {

void add_common_options(CLI::App& cmd, CommonOptions& o, bool with_iso) {
  if (with_iso)
    cmd.add_option("--iso", o.iso, "Isovalue (default: the volume's suggested isovalue, see isocurv info)");
  cmd.add_option("--device", o.device, "OpenCL device number from isocurv devices (default: a GPU, else PoCL's CPU device)");
  cmd.add_flag("--cap", o.cap, "Close surfaces cut by the volume's bounding box (default: leave them open)");
  cmd.add_option("--snap", o.snap,
                 "Move vertices closer than this fraction of a voxel to a voxel onto it and merge them "
                 "there (0..0.5; 0: off). Removes the slivers voxels equal to the isovalue leave; "
                 "snapped vertices leave the isosurface by up to this distance")
      ->check(CLI::Range(0.0, 0.5))->capture_default_str();
  cmd.add_flag("--json", o.json, "Print a JSON summary with timings_ms per stage on stdout");
  cmd.add_flag("--quiet", o.quiet, "No progress bars or messages on stderr");
  add_volume_options(cmd, o.volume);
  cmd.parse_complete_callback([&o] { set_progress_enabled(!o.quiet); });
}

void add_curvature_options(CLI::App& cmd, CommonOptions& o, bool mesh_input) {
  cmd.add_option("--normals", o.normals,
                 "Vertex normals: volume (from the volume's gradient, face normals where it points against the "
                 "faces or vanishes; the default for volume input) or mesh (from the faces, as Rusinkiewicz; "
                 "the default for mesh files)")
      ->check(CLI::IsMember({"mesh", "volume"}));
  if (mesh_input)
    cmd.add_flag("--flip", o.flip,
                 "Reverse the triangles of a mesh file before estimating (for a closed mesh oriented inward)");
  cmd.add_option("--ao-scale", o.ao_scale,
                 "Ambient-occlusion radius in world units (default: 4 x the mean edge length)")
      ->check(CLI::NonNegativeNumber);
}

void StageTimer::start(const std::string& stage) {
  stop();
  current_ = stage;
  t0_ = std::chrono::steady_clock::now();
}

void StageTimer::stop() {
  if (current_.empty()) return;
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0_).count();
  timings_[current_] = timings_.value(current_, 0.0) + std::round(ms * 1000) / 1000;
  current_.clear();
}

bool is_mesh_path(const std::string& path) {
  std::string lower = path;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  for (const char* ext : {".vtp", ".ply", ".obj", ".stl"})
    if (lower.size() > 4 && lower.compare(lower.size() - 4, 4, ext) == 0) return true;
  return false;
}

std::string format_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

Device& device_for(const CommonOptions& o) {
  static std::map<int, std::shared_ptr<Device>> opened;
  if (o.device < 0) return Device::default_device();
  auto& d = opened[o.device];
  if (!d) d = Device::open(o.device);
  return *d;
}

volume::Volume load_volume(const std::string& path, const CommonOptions& o, StageTimer& timer, float* iso) {
  timer.start("load");
  volume::Volume v = volume::load(path, to_load_options(o.volume));
  timer.stop();
  const float value = o.iso ? *o.iso : static_cast<float>(v.stats.suggested_isovalue);
  if (!std::isfinite(value))
    throw Error(path, "isovalue must be a finite number");
  if (o.iso && (value < v.stats.min || value > v.stats.max))
    throw Error(path, "isovalue " + format_number(value) + " is outside the value range [" +
                          format_number(v.stats.min) + ", " + format_number(v.stats.max) + "]");
  if (iso) *iso = value;
  return v;
}

Surface load_surface(const std::string& path, const CommonOptions& o, StageTimer& timer) {
  Surface s;
  if (is_mesh_path(path)) {
    timer.start("load");
    io::MeshFile f = io::read_mesh(path);
    timer.stop();
    s.mesh = std::move(f.mesh);
    s.field = std::move(f.field);
    return s;
  }
  s.volume = load_volume(path, o, timer, &s.isovalue);
  Device& dev = device_for(o);
  timer.start("extract");
  mc::Options mo;
  mo.cap = o.cap;
  mo.snap = o.snap;
  s.mesh = mc::extract(*s.volume, s.isovalue, dev, mo);
  timer.stop();
  return s;
}

void prepare_mesh_for_curvature(Surface& s, const std::string& path, const CommonOptions& o) {
  if (s.volume) {
    if (o.flip) throw Error(path, "--flip applies to mesh files only (an isosurface is always oriented outward)");
    return;
  }
  s.welded = curvature::weld_duplicates(s.mesh);
  if (s.welded > 0) s.field.reset();  // arrays carried by the file no longer match the vertices
  if (s.welded > 0 && !o.quiet)
    std::fprintf(stderr, "isocurv: note: %s: welded %zu duplicate vertices (exact copies) into %zu\n",
                 path.c_str(), s.welded, s.mesh.positions.size());
  if (o.flip) {
    for (Tri& t : s.mesh.triangles) std::swap(t[1], t[2]);
    s.flipped = true;
    s.field.reset();
  }
  const mc::MeshCheck c = mc::check_mesh(s.mesh);
  const double volume = c.closed_signed_volume();
  if (c.closed_components() > 0 && volume < 0)
    std::fprintf(stderr,
                 "isocurv: warning: %s: the closed mesh is oriented inward (signed volume %s), so H, k1 and k2 "
                 "come out with the wrong sign; %s\n",
                 path.c_str(), format_number(volume).c_str(),
                 o.flip ? "--flip made it so: drop --flip" : "--flip reverses its triangles");
}

curvature::CurvatureField estimate_curvature(const Mesh& mesh, const volume::Volume* volume,
                                             const CommonOptions& o, StageTimer& timer,
                                             NormalsUsed* used) {
  curvature::Options co;
  NormalsUsed chosen;
  chosen.source = o.normals.empty() ? (volume ? "volume" : "mesh") : o.normals;
  volume::MeshNormals normals;
  if (chosen.source == "volume") {
    if (!volume) throw Error("--normals volume needs a volume input, not a mesh file");
    timer.start("normals");
    normals = volume::gradient_normals_for_mesh(*volume, mesh);
    timer.stop();
    chosen.opposed = normals.opposed;
    chosen.weak = normals.weak;
    co.vertex_normals = &normals.normals;
  }
  if (used) *used = chosen;
  if (o.ao_scale > 0) {
    co.ao_scale = o.ao_scale;
  } else {
    co.ao_scale = curvature::default_ao_scale(mesh);
  }
  Device& dev = device_for(o);
  timer.start("curvature");
  curvature::CurvatureField field = curvature::estimate(mesh, dev, co);
  timer.stop();
  return field;
}

namespace {

nlohmann::json distribution_json(const curvature::Distribution& d) {
  if (d.empty) return nullptr;
  nlohmann::json j = {{"min", d.min}, {"max", d.max}, {"mean", d.mean}};
  for (std::size_t p = 0; p < curvature::kStatPercentiles.size(); ++p)
    j["p" + format_number(curvature::kStatPercentiles[p])] = d.percentiles[p];
  return j;
}

nlohmann::json field_stats_json(const curvature::CurvatureField& field, const Mesh& mesh) {
  const curvature::FieldStats st = curvature::field_stats(field, mean_edge_length(mesh));
  nlohmann::json cs;
  cs["H"] = distribution_json(st.H);
  cs["K"] = distribution_json(st.K);
  cs["k1"] = distribution_json(st.k1);
  cs["k2"] = distribution_json(st.k2);
  cs["weights"] = st.area_weighted ? "Area (per-vertex mixed area)" : "none (the field has no Area array)";
  cs["vertices_counted"] = st.counted;
  cs["unreliable_vertices"] = st.unreliable;
  cs["unreliable_above"] = st.unreliable_above;
  cs["unreliable_rule"] = "max(|k1|, |k2|) > 1 / (half the mean edge length)";
  cs["non_finite_vertices"] = st.non_finite;
  cs["excluded_from_statistics"] = "unreliable and non-finite vertices: left out of min, max, mean and "
                                   "every percentile of H, K, k1, k2";
  return cs;
}

}  // namespace

nlohmann::json surface_report(const Surface& s) {
  const mc::MeshCheck c = mc::check_mesh(s.mesh);
  nlohmann::json r = {{"vertices", c.vertices}, {"triangles", c.triangles}, {"area", c.area},
                      {"euler_characteristic", c.euler}, {"components", c.components},
                      {"boundary_edges", c.boundary_edges}, {"watertight", c.watertight()}};
  if (c.genus() >= 0) r["genus"] = c.genus();
  if (s.volume) r["isovalue"] = s.isovalue;
  if (!s.volume) {
    r["welded_vertices"] = s.welded;
    r["flipped"] = s.flipped;
  }
  if (!s.normals.source.empty()) {
    r["normals"] = s.normals.source;
    if (s.normals.source == "volume")
      r["normal_fallbacks"] = {{"count", s.normals.opposed + s.normals.weak},
                               {"opposed", s.normals.opposed},
                               {"weak_gradient", s.normals.weak},
                               {"rule", "face normal where the gradient normal points against the faces "
                                        "(dot <= 0) or the gradient is at most " +
                                        format_number(100 * volume::kWeakGradientFraction) +
                                        "% of its median over the vertices"}};
  }
  if (s.field && s.field->size() == s.mesh.positions.size())
    r["curvature"] = field_stats_json(*s.field, s.mesh);
  return r;
}

void write_text_file(const std::string& path, const std::string& text) {
  write_atomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw Error(path, "cannot write");
  });
}

}  // namespace isocurv::app
