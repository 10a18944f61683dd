#include "app/pipeline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

#include "app/picture_title.h"
#include "core/atomic_file.h"
#include "core/camera.h"
#include "core/error.h"
#include "core/lap.h"
#include "core/mesh_measures.h"
#include "core/program_cache.h"
#include "core/progress.h"
#include "ao/ao.h"
#include "curvature/ao_scale.h"
#include "curvature/multi_scale.h"
#include "curvature/estimate.h"
#include "curvature/field_stats.h"
#include "curvature/weld.h"
#include "curvature/reference.h"
#include "curvature/request.h"
#include "io/mesh_file.h"
#include "mc/extract.h"
#include "mc/extract_reference.h"
#include "mc/mesh_check.h"
#include "volume/gradient_normals.h"
#include "volume/isovalue_check.h"
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
  cmd.add_option("--snap", o.snap,
                 "Move vertices closer than this fraction of a voxel to a voxel onto it and merge them "
                 "there (0..0.5; 0: off). Removes the slivers voxels equal to the isovalue leave; "
                 "snapped vertices leave the isosurface by up to this distance")
      ->check(CLI::Range(0.0, 0.5))->capture_default_str();
  cmd.add_flag("--json", o.json, "Print a JSON summary with timings_ms per stage on stdout");
  cmd.add_flag("--quiet", o.quiet,
               "No progress bars or messages on stderr, and no summary line on stdout (--json still "
               "prints its report)");
  add_volume_options(cmd, o.volume);
  cmd.parse_complete_callback([&o] {
    set_progress_enabled(!o.quiet);
    set_program_cache_warnings(!o.quiet);
  });
}

void add_compress_option(CLI::App& cmd, CommonOptions& o) {
  cmd.add_option_function<std::string>(
         "--compress", [&o](const std::string& text) { o.compress = io::parse_compression(text); },
         "Compression of .vtp outputs: none, lz4[:LEVEL] or zlib[:LEVEL], LEVEL 1 (fastest, the "
         "default) to 9 (smallest); default lz4:1, several times faster to write than zlib")
      ->check([](const std::string& text) -> std::string {
        try {
          io::parse_compression(text);
          return "";
        } catch (const Error& e) {
          return e.what();
        }
      });
}

std::vector<std::string> parse_scales(const std::string& text) {
  std::vector<std::string> scales;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    scales.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  for (const std::string& s : scales) {
    if (s == "auto") {
      if (scales.size() > 1) throw Error("auto cannot be one of several scales ('" + text + "')");
      continue;
    }
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || *end != 0 || !std::isfinite(v) || !(v > 0))
      throw Error("a positive number (world units), a list of them, or auto, not '" + s + "'");
    if (std::count(scales.begin(), scales.end(), s) > 1)
      throw Error("scale " + s + " is given twice");
  }
  return scales;
}

namespace {

/// The curvature request of --estimator, --scale (its first value), --normals, --ao-scale,
/// --ao-method and --hattori-half.
curvature::Request curvature_request(const CommonOptions& o) {
  curvature::Request r;
  if (!o.estimator.empty()) {
    r.estimator = curvature::estimator_from_name(o.estimator);
    if (!r.estimator) throw Error("--estimator: unknown estimator '" + o.estimator + "'");
  }
  const std::optional<curvature::NormalsSource> normals = curvature::normals_from_name(o.normals);
  if (!normals) throw Error("--normals: unknown normals '" + o.normals + "'");
  r.normals = *normals;
  r.scale_given = o.scale != "auto";
  const std::vector<std::string> scales = parse_scales(o.scale);
  r.scale = scales[0] == "auto" ? 0.0 : std::strtod(scales[0].c_str(), nullptr);
  if (o.ao_scale > 0) r.ao_scale = o.ao_scale;
  if (!o.ao.empty()) {
    r.ao_method = ao::method_from_name(o.ao);
    if (!r.ao_method) throw Error("--ao-method: unknown method '" + o.ao + "'");
  }
  r.hattori_half = o.hattori_half;
  return r;
}

/// A curvature request's error (curvature::resolve, check_ao) in the command line's words: its
/// options (`o`, for the method named).
Error request_error(const curvature::RequestError& e, const CommonOptions& o) {
  const std::string name = curvature::estimator_name(e.estimator);
  switch (e.problem) {
    case curvature::RequestProblem::estimator_needs_volume:
      return Error("--estimator " + name +
                   " needs a volume input (it reads the volume's derivatives), not a mesh file");
    case curvature::RequestProblem::normals_not_for_volume:
      return Error("--normals applies to the mesh estimators; --estimator " + name +
                   " takes its normals from the volume's gradient at --scale");
    case curvature::RequestProblem::scale_not_for_mesh:
      return Error("--scale applies to --estimator volume");
    case curvature::RequestProblem::volume_normals_need_volume:
      return Error("--normals volume needs a volume input, not a mesh file");
    case curvature::RequestProblem::ao_needs_volume:
      return Error("--ao-method " + o.ao +
                   " needs a volume input (it casts rays through the volume), not a mesh file; "
                   "the curvature methods (griffin-exact, hattori, prantl) work on meshes");
    case curvature::RequestProblem::hattori_half_not_hattori:
      return Error("--hattori-half applies to --ao-method hattori");
    default:  // iso, the isovalue and the values: not asked by the command line's options
      break;
  }
  const char* option = "";
  switch (e.field) {
    case curvature::RequestField::estimator: option = "--estimator"; break;
    case curvature::RequestField::normals: option = "--normals"; break;
    case curvature::RequestField::scale: option = "--scale"; break;
    case curvature::RequestField::iso: option = "--iso"; break;
    case curvature::RequestField::ao_scale: option = "--ao-scale"; break;
    case curvature::RequestField::ao_method: option = "--ao-method"; break;
    case curvature::RequestField::hattori_half: option = "--hattori-half"; break;
  }
  return Error(std::string(option) + ": " + e.detail());
}

}  // namespace

curvature::NormalsSource mesh_estimators_normals(const CommonOptions& o, bool volume_input) {
  curvature::Request r;
  r.estimator = curvature::Estimator::rusinkiewicz;
  r.normals = curvature::normals_from_name(o.normals).value_or(curvature::NormalsSource::automatic);
  try {
    return curvature::resolve(r, volume_input).normals;
  } catch (const curvature::RequestError& e) {
    throw request_error(e, o);
  }
}

curvature::Estimator default_estimator(const CommonOptions& o, bool volume_input) {
  return curvature::default_estimator(curvature_request(o), volume_input);
}

void apply_estimator_parameters(const CommonOptions& o, curvature::Options& co) {
  if (o.batagelo_weights == "inverse-square")
    co.batagelo_weights = curvature::NeighbourWeights::inverse_square;
  const std::vector<std::string> scales = parse_scales(o.scale);
  co.scale = scales[0] == "auto" ? 0.0 : std::strtod(scales[0].c_str(), nullptr);
}

void add_curvature_options(CLI::App& cmd, CommonOptions& o, bool mesh_input) {
  cmd.add_option("--estimator", o.estimator,
                 "Curvature estimator: volume (from the volume's derivatives at --scale; the default "
                 "for volume input), rusinkiewicz (from the mesh; the default for mesh files, and "
                 "for volumes when --normals is given), or the other mesh estimators batagelo, "
                 "prantl3, prantl2, quadric, cubic, sampling, meyer (isocurv compare runs them all; "
                 "docs/curvature.md has the accuracy table)")
      ->check(CLI::IsMember(curvature::estimator_names()));
  cmd.add_option(
         "--scale", o.scale,
         "Volume estimator: the smoothing's standard deviation in world units (at least "
         "0.65 voxel), or auto (the "
         "default: from the voxel size, the voxel type and the noise measured near the "
         "surface); several, e.g. 1,2,4, add the scalar arrays at each scale suffixed _s<S> "
         "(H_s2), the first scale's also unsuffixed")
      ->check([](const std::string& s) -> std::string {
        try {
          parse_scales(s);
          return "";
        } catch (const Error& e) {
          return e.what();
        }
      });
  cmd.add_option("--normals", o.normals,
                 "Vertex normals for the mesh estimators: volume (from the volume's gradient, face normals "
                 "where it points against the faces or vanishes; the default for volume input), mesh (from "
                 "the faces with Max's weights, as Rusinkiewicz; the default for mesh files), area (face "
                 "normals weighted by area) or face-average (the plain average of unit face normals, "
                 "Batagelo's protocol)")
      ->check(CLI::IsMember(curvature::normals_names()));
  cmd.add_option("--batagelo-weights", o.batagelo_weights,
                 "--estimator batagelo: each 1-ring neighbour's weight in the one-pass tensor, uniform (the "
                 "default, as the paper) or inverse-square (1/|x|^2 of its offset in the tangent plane)")
      ->check(CLI::IsMember({"uniform", "inverse-square"}));
  if (mesh_input)
    cmd.add_flag("--flip", o.flip,
                 "Reverse the triangles of a mesh file before estimating (for a closed mesh oriented inward)");
  cmd.add_option("--ao-scale", o.ao_scale,
                 "Ambient-occlusion radius in world units (default: 4 x the mean edge length)")
      ->check(CLI::NonNegativeNumber);
}

void add_ao_options(CLI::App& cmd, CommonOptions& o) {
  cmd.add_option("--ao-method", o.ao,
                 "Ambient occlusion (the AO array): griffin (Griffin et al.'s polynomial, the "
                 "default), griffin-exact (the exact (k1, k2) integral it was fitted from), hattori, "
                 "prantl (mean-curvature mapping), raycast or raycast-cos (256 rays of length "
                 "--ao-scale through the volume, uniform or cosine-weighted; volume input only, "
                 "the reference)")
      ->check(CLI::IsMember(ao::method_names()));
  cmd.add_flag("--hattori-half", o.hattori_half,
               "--ao-method hattori: use the umbilic mean ao-scale (k1 + k2) / 2 instead of the printed "
               "ao-scale (k1 + k2)");
}

void apply_ao(const Mesh& mesh, curvature::CurvatureField& field, const volume::Volume* volume,
              float isovalue, const CommonOptions& o, StageTimer& timer) {
  const curvature::Request request = curvature_request(o);
  try {
    curvature::check_ao(request, volume != nullptr);
  } catch (const curvature::RequestError& e) {
    throw request_error(e, o);
  }
  curvature::Options co;
  co.ao_method = request.ao_method.value_or(ao::Method::griffin);
  co.hattori_half = request.hattori_half;
  if (co.ao_method == ao::Method::griffin) return;
  co.ao_scale = request.ao_scale ? *request.ao_scale : curvature::default_ao_scale(mesh);
  timer.start("ao");
  curvature::apply_ao(mesh, field, {volume, isovalue}, co);
  timer.stop();
}

void StageTimer::start(const std::string& stage) {
  stop();
  current_ = stage;
  bar_ = std::make_unique<StageBar>(stage);
  compile0_ = program_build_stats().ms;
  t0_ = std::chrono::steady_clock::now();
}

void StageTimer::move(const std::string& from, const std::string& to, double ms) {
  auto add = [&](const std::string& key, double v) {
    timings_[key] = std::round((timings_.value(key, 0.0) + v) * 1000) / 1000;
  };
  add(from, -ms);
  add(to, ms);
}

void StageTimer::stop() {
  bar_.reset();
  if (current_.empty()) return;
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0_).count();
  const double compile = std::min(ms, program_build_stats().ms - compile0_);
  auto add = [&](const std::string& key, double v) {
    timings_[key] = std::round((timings_.value(key, 0.0) + v) * 1000) / 1000;
  };
  add(current_, ms - compile);
  if (compile > 0) add("compile", compile);
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
  mo.snap = o.snap;
  if (reference_device(o)) return mc::extract_reference(v, isovalue, mo);
  return mc::extract(v, isovalue, device_for(o), mo);
}

volume::Volume load_volume(const std::string& path, const CommonOptions& o, StageTimer& timer, float* iso) {
  timer.start("load");
  volume::Volume v = volume::load(path, to_load_options(o.volume));
  timer.stop();
  const float value = checked_isovalue(path, v, o.iso);
  if (iso) *iso = value;
  return v;
}

float checked_isovalue(const std::string& path, const volume::Volume& v,
                       std::optional<float> requested) {
  try {
    return volume::checked_isovalue(v, requested);
  } catch (const volume::IsovalueError& e) {
    throw Error(path, e.what());
  }
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

}  // namespace

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

Surface load_surface(const std::string& path, const CommonOptions& o, StageTimer& timer,
                     EmptySurface empty) {
  if (o.labelled())  // the commands take labels one map at a time (app/label_surfaces.h)
    throw Error(path, "--labels takes one label map at a time, not a batch, a sweep or a time series");
  Surface s;
  if (is_mesh_path(path)) {
    reject_volume_options(path, o);
    timer.start("load");
    io::MeshFile f = io::read_mesh(path);
    timer.stop();
    s.mesh = std::move(f.mesh);
    s.field = std::move(f.field);
    s.file_metadata = std::move(f.metadata);
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

void reestimate_keeping_extras(Surface& s, const std::string& path, const CommonOptions& o,
                               StageTimer& timer) {
  std::vector<curvature::CurvatureField::Named> extras;
  if (s.field) extras = std::move(s.field->extra);
  prepare_mesh_for_curvature(s, path, o);
  curvature::CurvatureField f = estimate_curvature(s.mesh, s.volume ? &*s.volume : nullptr,
                                                   s.isovalue, o, timer, &s.normals, &s.estimator);
  const std::size_t nv = s.mesh.positions.size();
  for (auto& e : extras) {
    const bool present = std::any_of(f.extra.begin(), f.extra.end(),
                                     [&](const auto& x) { return x.name == e.name; });
    if (e.values.size() == nv && !present && s.welded == 0) f.extra.push_back(std::move(e));
  }
  s.field = std::move(f);
}

curvature::CurvatureField estimate_curvature(const Mesh& mesh, const volume::Volume* volume,
                                             float isovalue, const CommonOptions& o,
                                             StageTimer& timer, NormalsUsed* used,
                                             curvature::EstimatorReport* report,
                                             const SurfacePiece* piece) {
  curvature::Resolved request;
  try {
    request = curvature::resolve(curvature_request(o), volume != nullptr,
                                 volume ? std::optional<float>(isovalue) : std::nullopt);
  } catch (const curvature::RequestError& e) {
    throw request_error(e, o);
  }
  curvature::Options co;
  co.piece = piece;
  co.estimator = request.estimator;
  co.ao_method = request.ao_method;
  co.hattori_half = request.hattori_half;
  if (!o.batagelo_weights.empty() && co.estimator != curvature::Estimator::batagelo)
    throw Error("--batagelo-weights applies to --estimator batagelo");
  apply_estimator_parameters(o, co);
  const std::vector<std::string> scales = parse_scales(o.scale);  // several: arrays per scale, below
  NormalsUsed chosen;
  chosen.source = curvature::normals_report_name(request);
  // area, face-average and volume normals: computed here, so that every mesh estimator gets them
  if (request.normals == curvature::NormalsSource::volume) timer.start("normals");
  const volume::MeshNormals normals = curvature::host_normals(request.normals, mesh, volume, o.cap);
  if (request.normals == curvature::NormalsSource::volume) timer.stop();
  if (curvature::host_computed(request.normals)) co.vertex_normals = &normals.normals;
  chosen.opposed = normals.opposed;
  chosen.weak = normals.weak;
  chosen.caps = normals.caps;
  if (used) *used = chosen;
  co.ao_scale = request.ao_scale ? *request.ao_scale : curvature::default_ao_scale(mesh, piece);
  if (!reference_device(o)) device_for(o);  // open the device (and fail on it) before timing
  timer.start("curvature");
  curvature::EstimatorReport r;
  Device* device = reference_device(o) ? nullptr : &device_for(o);
  if (scales.size() > 1) co.finer_scales = false;  // each scale shows only what it resolves
  // The AO (co.ao_method) is estimate_field's last step; with several scales it runs once, on
  // the first scale's curvature, after the other scales' arrays.
  curvature::Options first = co;
  if (scales.size() > 1) first.ao_method = ao::Method::griffin, first.hattori_half = false;
  curvature::CurvatureField field = curvature::estimate_field(mesh, {volume, isovalue}, device, first, &r);
  if (scales.size() > 1) {
    // Every scale's scalar arrays under its suffix; the first scale's also stay unsuffixed.
    curvature::append_scale_arrays(field, scales[0], field);
    for (std::size_t i = 1; i < scales.size(); ++i) {
      curvature::Options at = first;
      at.scale = std::strtod(scales[i].c_str(), nullptr);
      curvature::append_scale_arrays(
          curvature::estimate_field(mesh, {volume, isovalue}, device, at), scales[i], field);
    }
    r.notes.emplace_back("scales", o.scale);
    field.metadata.emplace_back("scales", o.scale);
    StepClock::time_point t = StepClock::now();
    if (curvature::apply_ao(mesh, field, {volume, isovalue}, co)) r.ao_ms = lap(t);
  }
  timer.stop();
  if (r.ao_ms) timer.move("curvature", "ao", *r.ao_ms);  // reported as its own stage
  if (report) *report = std::move(r);
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
  cs["unmeasured_vertices"] = st.unmeasured;
  cs["unreliable_vertices"] = st.unreliable;
  cs["unreliable_above"] = st.unreliable_above;
  cs["unreliable_rule"] = "max(|k1|, |k2|) > 1 / (half the mean edge length)";
  cs["non_finite_vertices"] = st.non_finite;
  cs["excluded_from_statistics"] = "unmeasured (flagged Unreliable by the estimator), unreliable and "
                                   "non-finite vertices: left out of min, max, mean and every percentile "
                                   "of H, K, k1, k2";
  return cs;
}

}  // namespace

nlohmann::json surface_report(const Surface& s) {
  const mc::MeshCheck c = mc::check_mesh(s.mesh);
  nlohmann::json r = {{"vertices", c.vertices}, {"triangles", c.triangles}, {"area", c.area},
                      {"euler_characteristic", c.euler}, {"components", c.components},
                      {"boundary_edges", c.boundary_edges}, {"watertight", c.watertight()}};
  if (c.genus() >= 0) r["genus"] = c.genus();
  if (s.volume && s.label_parts.empty()) r["isovalue"] = s.isovalue;
  if (!s.label_parts.empty()) {
    r["labels"] = nlohmann::json::array();
    for (const labels::LabelPart& p : s.label_parts)
      r["labels"].push_back({{"label", p.value}, {"vertices", p.vertices}, {"triangles", p.triangles}});
  }
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
    if (s.normals.source == "volume" && s.normals.caps > 0) r["cap_vertices_with_box_normals"] = s.normals.caps;
  }
  if (!s.estimator.estimator.empty()) {
    nlohmann::json e = {{"name", s.estimator.estimator}};
    for (const auto& [key, value] : s.estimator.parameters) e[key] = value;
    for (const auto& [key, how] : s.estimator.notes) {
      if (key == "scales")
        e["scales"] = parse_scales(how);  // --scale S1,S2,...: arrays suffixed _s<S> per scale
      else if (key == "neighbour_weights")
        e[key] = how;  // --batagelo-weights
      else
        e[key + "_chosen"] = how;
    }
    e["implausible_vertices"] = s.estimator.implausible;  // flagged by the one rule (field_stats.h)
    if (s.estimator.estimator == "volume") {
      e["unreliable_vertices"] = s.estimator.unreliable;
      e["finer_scale_vertices"] = s.estimator.finer_scale;
      e["outside_box_vertices"] = s.estimator.outside;
      const std::vector<float>* scale = s.field ? s.field->find_extra("Scale") : nullptr;
      if (scale && !scale->empty()) {
        // The per-vertex scale (world units): its distribution over the vertices.
        std::vector<float> v = *scale;
        std::sort(v.begin(), v.end());
        auto at = [&](double p) { return double(v[std::size_t(p * double(v.size() - 1))]); };
        const bool chosen = e.value("scale_chosen", "").rfind("auto", 0) == 0;
        nlohmann::json d = {{"min", at(0)},    {"p5", at(0.05)}, {"p50", at(0.5)},
                            {"p95", at(0.95)}, {"max", at(1)},
                            {"rule", chosen ? "per vertex, noise against bias and the "
                                              "shape's limit, then finer while the smoothing "
                                              "erodes the vertex's surface or merges it with "
                                              "another (docs/curvature.md)"
                                            : "the asked scale, divided by sqrt(2) down to "
                                              "0.8 voxel while the smoothing erodes the "
                                              "vertex's surface or merges it with another "
                                              "(docs/curvature.md)"}};
        if (s.volume) {  // the same in voxels of the geometric mean spacing
          const openvdb::Vec3d h = s.volume->spacing();
          const double voxel = std::cbrt(h[0] * h[1] * h[2]);
          d["voxels"] = {{"min", at(0) / voxel},    {"p5", at(0.05) / voxel},
                         {"p50", at(0.5) / voxel},  {"p95", at(0.95) / voxel},
                         {"max", at(1) / voxel}};
        }
        e["scale_per_vertex"] = d;
      }
    }
    if (s.estimator.estimator == "volume")
      e["pyramid_bricks_kept"] = s.estimator.pyramid_bricks_kept;
    if (!s.estimator.steps_ms.empty()) {
      nlohmann::json steps = nlohmann::json::object();
      for (const auto& [step, ms] : s.estimator.steps_ms) steps[step] = ms;
      e["steps_ms"] = steps;
    }
    r["estimator"] = e;
  }
  if (s.field && !s.field->ao.empty()) {  // which AO the field carries (ao/ao.h's metadata)
    nlohmann::json a = nlohmann::json::object();
    for (const auto& [key, value] : s.field->metadata)
      if (key == "ao") a["method"] = value;
      else if (key.rfind("ao_", 0) == 0 && key != "ao_scale") a[key.substr(3)] = value;
    double sum = 0;
    for (float v : s.field->ao) sum += v;
    a["mean"] = sum / double(s.field->ao.size());
    if (a.contains("method")) r["ao"] = a;
  }
  if (s.field && s.field->size() == s.mesh.positions.size())
    r["curvature"] = field_stats_json(*s.field, s.mesh);
  return r;
}

SurfaceContext surface_context(const Surface& s) {
  SurfaceContext c;
  if (s.volume) {
    if (s.label_parts.empty()) c.isovalue = s.isovalue;  // labels: each at its indicator's half
    c.length_unit = s.volume->length_unit;
    c.world_space = s.volume->world_space;
    return c;
  }
  curvature::EstimatorReport made;
  for (const auto& [key, value] : s.file_metadata) {
    if (key == "isovalue") {
      char* end = nullptr;
      const float iso = std::strtof(value.c_str(), &end);
      if (end != value.c_str() && *end == 0 && std::isfinite(iso)) c.isovalue = iso;
    } else if (key == "length_unit") {
      c.length_unit = value;
    } else if (key == "world_space") {
      if (anatomical_frame_named(value)) c.world_space = value;
    } else if (key == "estimator") {
      made.estimator = value;
    } else if (key == "feature_radius") {
      c.feature_radius = value;
    } else if (key == "scale" || key == "scale_p5" || key == "scale_p95") {
      char* end = nullptr;
      const double scale = std::strtod(value.c_str(), &end);
      if (end != value.c_str() && *end == 0 && std::isfinite(scale))
        made.parameters.emplace_back(key, scale);
    }
  }
  if (!made.estimator.empty()) c.file_estimator = estimator_title(made);
  return c;
}

io::Metadata context_metadata(const Surface& s, const std::string& input,
                              const std::string& length_unit) {
  const SurfaceContext c = surface_context(s);
  io::Metadata m;
  if (c.isovalue) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", double(*c.isovalue));
    m.emplace_back("isovalue", buf);
  }
  const std::string unit = length_unit.empty() ? c.length_unit : length_unit;
  if (!unit.empty()) m.emplace_back("length_unit", unit);
  if (!c.world_space.empty()) m.emplace_back("world_space", c.world_space);
  if (!s.label_parts.empty()) {  // which labels the mesh holds, as "1,2,5" (at most 1,000 bytes)
    std::string list;
    for (const labels::LabelPart& p : s.label_parts) {
      const std::string item = std::to_string(p.value);
      if (list.size() + item.size() + 5 > 1000) {
        list += ",...";
        break;
      }
      list += (list.empty() ? "" : ",") + item;
    }
    m.emplace_back("labels", list);
  }
  std::string source = s.volume ? input : "";
  for (const auto& [key, value] : s.file_metadata)
    if (key == "source") source = value;  // a mesh file keeps the volume it came from
  if (!source.empty()) m.emplace_back("source", std::filesystem::path(source).filename().string());
  return m;
}

nlohmann::json program_report() {
  const ProgramBuildStats st = program_build_stats();
  const std::string dir = program_cache_dir();
  return {{"compiled", st.compiled},
          {"from_cache", st.from_cache},
          {"rejected", st.rejected},
          {"cache_dir", dir.empty() ? nlohmann::json(nullptr) : nlohmann::json(dir)}};
}

std::uint64_t file_bytes(const std::string& path) {
  std::error_code ec;
  const auto n = std::filesystem::file_size(path, ec);
  return ec ? 0 : std::uint64_t(n);
}

std::string format_bytes(std::uint64_t bytes) {
  char buf[32];
  if (bytes >= 1000000) std::snprintf(buf, sizeof buf, "%.2f MB", double(bytes) / 1e6);
  else if (bytes >= 1000) std::snprintf(buf, sizeof buf, "%.1f kB", double(bytes) / 1e3);
  else std::snprintf(buf, sizeof buf, "%llu bytes", static_cast<unsigned long long>(bytes));
  return buf;
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
