#include "app/pipeline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/progress.h"
#include "curvature/ao_scale.h"
#include "curvature/estimate.h"
#include "curvature/reference.h"
#include "io/mesh_file.h"
#include "mc/extract.h"
#include "mc/extract_reference.h"
#include "mc/mesh_check.h"
#include "volume/gradient_normals.h"
#include "volume/load.h"

namespace isocurv::app {

void add_common_options(CLI::App& cmd, CommonOptions& o, bool with_iso) {
  if (with_iso)
    cmd.add_option("--iso", o.iso, "Isovalue (default: the volume's suggested isovalue, see isocurv info)");
  cmd.add_option(
         "--device", o.device,
         "OpenCL device number from isocurv devices (default: a GPU, else PoCL's CPU device), or "
         "'reference': the plain C++ mesher and double-precision curvature, slow but needing "
         "no OpenCL")
      ->check([](const std::string& v) -> std::string {
        if (v == "reference" ||
            (!v.empty() && v.find_first_not_of("0123456789") == std::string::npos))
          return "";
        return "expected a device number (see isocurv devices) or 'reference', not '" + v + "'";
      });
  cmd.add_flag("--cap", o.cap, "Close surfaces cut by the volume's bounding box (default: leave them open)");
  cmd.add_flag("--json", o.json, "Print a JSON summary with timings_ms per stage on stdout");
  cmd.add_flag("--quiet", o.quiet, "No progress bars or messages on stderr");
  add_volume_options(cmd, o.volume);
  cmd.parse_complete_callback([&o] { set_progress_enabled(!o.quiet); });
}

void add_curvature_options(CLI::App& cmd, CommonOptions& o) {
  cmd.add_option("--normals", o.normals,
                 "Vertex normals: mesh (from the faces, as Rusinkiewicz) or volume (from the volume's gradient; "
                 "more accurate on marching-cubes meshes)")
      ->check(CLI::IsMember({"mesh", "volume"}))->capture_default_str();
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

bool reference_device(const CommonOptions& o) {
  if (!o.device.empty()) return o.device == "reference";
  const char* env = std::getenv("ISOCURV_DEVICE");
  return env && std::string(env) == "reference";
}

Device& device_for(const CommonOptions& o) {
  if (reference_device(o)) throw Error("internal: device_for called for --device reference");
  static std::map<int, std::shared_ptr<Device>> opened;
  try {
    if (o.device.empty()) return Device::default_device();
    const int index = std::stoi(o.device);
    auto& d = opened[index];
    if (!d) d = Device::open(index);
    return *d;
  } catch (const NoOpenCL& e) {
    throw Error(std::string(e.what()) +
                "; or run with --device reference (the C++ references: slow, no OpenCL)");
  } catch (const std::out_of_range&) {
    throw Error("no OpenCL device number " + o.device + " (see isocurv devices)");
  }
}

std::string device_name(const CommonOptions& o) {
  return reference_device(o) ? "reference (C++ mesher, double-precision curvature)"
                             : device_for(o).info().name;
}

Mesh extract_surface(const volume::Volume& v, float isovalue, const CommonOptions& o) {
  mc::Options mo;
  mo.cap = o.cap;
  if (reference_device(o)) return mc::extract_reference(v, isovalue, mo);
  return mc::extract(v, isovalue, device_for(o), mo);
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
  // The tie rule: a voxel equal to the isovalue is outside, so at the top of the range (bottom
  // when the object is below the isovalue) no voxel is inside and there is no surface.
  const bool above = v.inside == volume::Inside::Above;
  if (value == static_cast<float>(above ? v.stats.max : v.stats.min))
    throw Error(path, "isovalue " + format_number(value) + " equals the " +
                          (above ? "maximum" : "minimum") +
                          " value, so there is no surface: a voxel equal to the isovalue counts as "
                          "outside, and none is " + (above ? "above" : "below") +
                          " it (the range is [" + format_number(v.stats.min) + ", " +
                          format_number(v.stats.max) + "])");
  if (iso) *iso = value;
  return v;
}

namespace {

/// Volume options that cannot apply to a mesh file are errors, not silently ignored.
void reject_volume_options(const std::string& path, const CommonOptions& o) {
  std::vector<std::string> given = o.volume.given();
  if (o.iso) given.insert(given.begin(), "--iso");
  if (o.cap) given.push_back("--cap");
  if (!given.empty())
    throw Error(path, given.front() + " applies to volumes only, and this is a mesh file");
}

/// The one rule for an isosurface without triangles (see EmptySurface).
void handle_empty_surface(const Surface& s, const std::string& path, const CommonOptions& o,
                          EmptySurface empty) {
  if (!s.mesh.triangles.empty()) return;
  const std::string problem = "isovalue " + format_number(s.isovalue) +
                              " gives no surface (the values range over [" +
                              format_number(s.volume->stats.min) + ", " +
                              format_number(s.volume->stats.max) + "]; see isocurv info)";
  if (empty == EmptySurface::error) throw Error(path, problem);
  if (!o.quiet)
    std::fprintf(stderr, "isocurv: warning: %s: %s; writing an empty mesh\n", path.c_str(),
                 problem.c_str());
}

}  // namespace

Surface load_surface(const std::string& path, const CommonOptions& o, StageTimer& timer,
                     EmptySurface empty) {
  Surface s;
  if (is_mesh_path(path)) {
    reject_volume_options(path, o);
    timer.start("load");
    io::MeshFile f = io::read_mesh(path);
    timer.stop();
    s.mesh = std::move(f.mesh);
    s.field = std::move(f.field);
    return s;
  }
  s.volume = load_volume(path, o, timer, &s.isovalue);
  if (!reference_device(o)) device_for(o);  // open the device (and fail on it) before timing
  timer.start("extract");
  s.mesh = extract_surface(*s.volume, s.isovalue, o);
  timer.stop();
  handle_empty_surface(s, path, o, empty);
  return s;
}

void require_curvature_format(const std::string& path) {
  std::string lower = path;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  for (const char* ext : {".vtp", ".ply"})
    if (lower.size() > 4 && lower.compare(lower.size() - 4, 4, ext) == 0) return;
  if (is_mesh_path(path))
    throw Error(path,
                "this format cannot hold the curvature arrays: write .vtp or .ply (extract writes "
                ".obj and .stl)");
  throw Error(path, "unknown mesh extension: write .vtp or .ply (they carry the curvature arrays)");
}

curvature::CurvatureField estimate_curvature(const Mesh& mesh, const volume::Volume* volume,
                                             const CommonOptions& o, StageTimer& timer) {
  curvature::Options co;
  std::vector<Vec3f> normals;
  if (o.normals == "volume") {
    if (!volume) throw Error("--normals volume needs a volume input, not a mesh file");
    timer.start("normals");
    normals = volume::gradient_normals(*volume, mesh.positions);
    timer.stop();
    co.vertex_normals = &normals;
  }
  if (o.ao_scale > 0) {
    co.ao_scale = o.ao_scale;
  } else {
    co.ao_scale = curvature::default_ao_scale(mesh);
  }
  if (!reference_device(o)) device_for(o);  // open the device (and fail on it) before timing
  timer.start("curvature");
  curvature::CurvatureField field = reference_device(o)
                                        ? curvature::estimate_reference(mesh, co)
                                        : curvature::estimate(mesh, device_for(o), co);
  timer.stop();
  return field;
}

namespace {

nlohmann::json distribution(const std::vector<float>& values) {
  std::vector<float> v;
  v.reserve(values.size());
  for (float x : values)
    if (std::isfinite(x)) v.push_back(x);
  if (v.empty()) return nullptr;
  std::sort(v.begin(), v.end());
  double sum = 0;
  for (float x : v) sum += x;
  auto pct = [&v](double p) { return double(v[std::min(v.size() - 1, std::size_t(p / 100.0 * (v.size() - 1) + 0.5))]); };
  return {{"min", v.front()}, {"max", v.back()}, {"mean", sum / v.size()},
          {"p1", pct(1)}, {"p5", pct(5)}, {"p25", pct(25)}, {"p50", pct(50)}, {"p75", pct(75)},
          {"p95", pct(95)}, {"p99", pct(99)}};
}

}  // namespace

nlohmann::json surface_report(const Surface& s) {
  const mc::MeshCheck c = mc::check_mesh(s.mesh);
  nlohmann::json r = {{"vertices", c.vertices}, {"triangles", c.triangles}, {"area", c.area},
                      {"euler_characteristic", c.euler}, {"components", c.components},
                      {"boundary_edges", c.boundary_edges}, {"watertight", c.watertight()}};
  if (c.genus() >= 0) r["genus"] = c.genus();
  if (s.volume) r["isovalue"] = s.isovalue;
  if (s.field && s.field->size() == s.mesh.positions.size()) {
    nlohmann::json cs;
    cs["H"] = distribution(s.field->H);
    cs["K"] = distribution(s.field->K);
    cs["k1"] = distribution(s.field->k1);
    cs["k2"] = distribution(s.field->k2);
    r["curvature"] = cs;
  }
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
