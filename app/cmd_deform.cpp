// isocurv deform MESH --deformer affine|noise|skin -o DIR: an animated mesh (connectivity fixed),
// deformed on the device frame by frame, curvature on a prepared topology, one .vtp per frame.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/batch.h"
#include "app/commands.h"
#include "app/pipeline.h"
#include "core/device_call.h"
#include "core/error.h"
#include "core/lap.h"
#include "core/mesh_measures.h"
#include "core/progress.h"
#include "curvature/ao_scale.h"
#include "curvature/estimator.h"
#include "curvature/topology.h"
#include "deform/affine.h"
#include "deform/noise_displace.h"
#include "deform/skinning.h"
#include "io/mesh_file.h"
#include "io/pvd_collection.h"

namespace isocurv::app {
namespace {

namespace fs = std::filesystem;
using Clock = StepClock;

struct DeformCli {
  std::string input, output, deformer, skin, estimator = "rusinkiewicz";
  int frames = 60;
  double amplitude = 0.02;  // noise: fraction of the bounding-box diagonal
  double waves = 4;         // noise: wavelengths per bounding-box diagonal
};

std::string frame_name(const std::string& stem, int f) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "_%04d.vtp", f);
  return stem + buf;
}

void run_deform(const DeformCli& c, const CommonOptions& o) {
  if (c.deformer != "affine" && c.deformer != "noise" && c.deformer != "skin")
    throw Error("--deformer must be affine, noise or skin, not '" + c.deformer + "'");
  if (c.deformer == "skin" && c.skin.empty()) throw Error("--deformer skin needs --skin FILE.json");
  if (c.deformer != "skin" && !c.skin.empty())
    throw Error("--skin applies to --deformer skin only");
  if (c.frames < 1 || c.frames > 100000) throw Error("--frames must be between 1 and 100000");
  if (!std::isfinite(c.amplitude) || !std::isfinite(c.waves) || c.waves <= 0)
    throw Error("--amplitude must be finite and --waves positive");
  // Only the estimators with a prepared path (curvature/topology.h): the others are refused by
  // name, in one line that lists those deform takes.
  const std::optional<curvature::Estimator> est = curvature::estimator_from_name(c.estimator);
  if (!est)
    throw Error("--estimator must be one of " + curvature::prepared_estimator_names() +
                " (the estimators with a prepared-topology path), not '" + c.estimator + "'");
  if (!curvature::has_prepared_path(*est))
    throw Error("--estimator " + c.estimator + ": deform runs only " +
                curvature::prepared_estimator_names() + "; " +
                curvature::no_prepared_path_reason(*est));
  if (!is_mesh_path(c.input))
    throw Error(c.input + ": deform takes a mesh file (" + io::mesh_extensions() + ")");
  if (reference_device(o))
    throw Error("deform runs on an OpenCL device (--device reference has no deformer kernels)");

  StageTimer timer;
  Surface s = load_surface(c.input, o, timer);
  const Mesh& rest = s.mesh;
  if (rest.triangle_count() == 0) throw Error(c.input + ": the mesh has no triangles");
  std::optional<deform::Skin> skin;
  if (c.deformer == "skin") skin = deform::load_skin(c.skin, rest.vertex_count());
  // Every frame's time, checked before anything is written: the .pvd needs them finite and
  // increasing (a one-keyframe rig once wrote its frames, then failed naming the .pvd).
  // Time: one period over the frames for the analytic deformers, the keyframe span for a skin.
  std::vector<double> times(std::size_t(c.frames));
  for (int f = 0; f < c.frames; ++f) {
    double t = double(f) / c.frames;
    if (skin)
      t = c.frames == 1
              ? skin->start_time()
              : skin->start_time() + (skin->end_time() - skin->start_time()) * f / (c.frames - 1);
    times[std::size_t(f)] = t;
  }
  if (skin && c.frames > 1 && skin->keyframes.size() < 2)
    throw Error("deform: " + c.skin + ": the rig has one keyframe, so all " + std::to_string(c.frames) +
                " frames would have the same time; give two keyframes or more, or --frames 1");
  for (std::size_t f = 0; skin && f < times.size(); ++f)
    if (!std::isfinite(times[f]) || (f > 0 && !(times[f] > times[f - 1])))
      throw Error("deform: " + c.skin + ": the keyframe times " + std::to_string(skin->start_time()) + " to " +
                  std::to_string(skin->end_time()) + " cannot give " + std::to_string(c.frames) +
                  " distinct, finite frame times");

  // Everything is checked: now the output folder.
  require_folder_name(c.output, "deform");
  std::error_code ec;
  fs::create_directories(c.output, ec);
  if (ec || !fs::is_directory(c.output))
    throw Error(c.output + ": cannot create the output folder");
  const std::string stem = file_stem(c.input, "mesh");

  Device& dev = device_for(o);
  timer.start("prepare");
  curvature::Topology topo = curvature::prepare(rest.triangles, rest.vertex_count(), dev);
  curvature::Options co;
  co.estimator = *est;
  co.ao_scale = o.ao_scale > 0 ? o.ao_scale : curvature::default_ao_scale(rest);
  const std::size_t nv = rest.vertex_count();
  cl::Buffer rest_buf;
  std::optional<cl::Buffer> normals_buf;
  std::unique_ptr<deform::DeviceSkin> device_skin;
  const double diag = bounding_box_diagonal(rest);
  device_call(dev, "deform: uploading the mesh", [&] {
    rest_buf = cl::Buffer(dev.context(), CL_MEM_READ_ONLY, nv * sizeof(Vec3f));
    dev.queue().enqueueWriteBuffer(rest_buf, CL_TRUE, 0, nv * sizeof(Vec3f), rest.positions.data());
    if (c.deformer == "noise") {
      const std::vector<Vec3f> n = area_weighted_normals(rest);
      normals_buf = cl::Buffer(dev.context(), CL_MEM_READ_ONLY, nv * sizeof(Vec3f));
      dev.queue().enqueueWriteBuffer(*normals_buf, CL_TRUE, 0, nv * sizeof(Vec3f), n.data());
    }
    if (skin) device_skin = std::make_unique<deform::DeviceSkin>(dev, *skin);
    dev.queue().finish();
  });
  timer.stop();

  io::PvdCollection pvd((fs::path(c.output) / (stem + ".pvd")).string());
  nlohmann::json per_frame = nlohmann::json::array();
  double sum_deform = 0, sum_curv = 0, sum_write = 0;
  Mesh frame;
  frame.triangles = rest.triangles;
  frame.positions.resize(nv);
  curvature::CurvatureField field;
  Progress bar("deform", std::uint64_t(c.frames));
  for (int f = 0; f < c.frames; ++f) {
    const double t = times[std::size_t(f)];
    Clock::time_point clock = Clock::now();
    if (c.deformer == "affine") {
      const std::array<double, 3> a = deform::ellipsoid_axes(t);
      deform::affine(dev, rest_buf, nv, deform::scaling(a[0], a[1], a[2]), topo.positions());
    } else if (c.deformer == "noise") {
      const double amp = c.amplitude * diag * std::sin(2 * 3.14159265358979323846 * t);
      deform::noise_displace(dev, rest_buf, *normals_buf, nv,
                             2 * 3.14159265358979323846 * c.waves / diag, amp, topo.positions());
    } else {
      device_skin->apply(rest_buf, deform::bone_matrices(*skin, t), topo.positions());
    }
    device_call(dev, "deform", [&] { dev.queue().finish(); });
    const double deform_ms = lap(clock);
    curvature::Timings ct;
    curvature::estimate_resident(co.estimator, topo, dev, co, field, &ct);
    const double curv_ms = lap(clock);
    device_call(dev, "deform: reading the positions", [&] {
      dev.queue().enqueueReadBuffer(topo.positions(), CL_TRUE, 0, nv * sizeof(Vec3f),
                                    frame.positions.data());
    });
    const std::string name = frame_name(stem, f);
    const std::string path = (fs::path(c.output) / name).string();
    io::write_mesh(path, frame, &field, o.compress);
    pvd.add(t, path);
    const double write_ms = lap(clock);
    sum_deform += deform_ms, sum_curv += curv_ms, sum_write += write_ms;
    per_frame.push_back(
        {{"frame", f},
         {"time", t},
         {"file", name},
         {"timings_ms", {{"deform", deform_ms}, {"curvature", curv_ms}, {"write", write_ms}}}});
    bar.advance();
  }
  bar.finish();

  const double per_frame_ms = (sum_deform + sum_curv) / c.frames;
  nlohmann::json r;
  r["input"] = c.input;
  r["deformer"] = c.deformer;
  if (skin) r["skin"] = c.skin;
  r["estimator"] = c.estimator;
  r["frames"] = c.frames;
  r["vertices"] = nv;
  r["triangles"] = rest.triangle_count();
  r["device"] = device_name(o);
  r["collection"] = stem + ".pvd";
  r["timings_ms"] = timer.json();
  r["timings_ms"]["deform"] = sum_deform;
  r["timings_ms"]["curvature"] = sum_curv;
  r["timings_ms"]["write"] = sum_write;
  r["frames_per_second"] = per_frame_ms > 0 ? 1000.0 / per_frame_ms : 0.0;
  r["per_frame"] = per_frame;
  write_text_file((fs::path(c.output) / "timings.json").string(), r.dump(2) + "\n");
  if (o.json) {
    r.erase("per_frame");
    r["programs"] = program_report();
    std::cout << r.dump(2) << "\n";
  } else if (!o.quiet) {
    std::printf(
        "wrote %d frames of %zu vertices to %s (%s.pvd, timings.json): %.2f ms a frame "
        "deform + curvature, %.1f frames/s\n",
        c.frames, nv, c.output.c_str(), stem.c_str(), per_frame_ms,
        r["frames_per_second"].get<double>());
  }
}

}  // namespace

void register_deform(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "deform",
      "Animate a mesh on the device (affine ellipsoid, noise displacement or linear-blend "
      "skinning; connectivity fixed) and estimate its curvature every frame on a prepared "
      "topology: one .vtp per frame, a .pvd collection and timings.json");
  cmd->footer(
      "Example: isocurv deform sphere.vtp --deformer affine --frames 60 -o anim/\n"
      "         isocurv deform build/datasets/finger.vtp --deformer skin\n"
      "           --skin build/datasets/finger_rig.json --frames 9 -o finger/  (the sample rig)\n"
      "affine: scaled about the origin by diag(a, b, c), a = 1 + 0.5 sin 2 pi t and b, c a third\n"
      "and two thirds of a period later (a unit sphere becomes ellipsoids with axes in [0.5,\n"
      "1.5]); noise: p + A sin(2 pi t) noise(p) n along the rest normals "
      "(deform/noise_displace.h);\n"
      "t = frame / frames. skin: the keyframes of --skin (format: docs/time-series.md)\n"
      "sampled evenly from the first to the last. Writes DIR/<stem>_NNNN.vtp, DIR/<stem>.pvd\n"
      "(rewritten as each frame is added) and DIR/timings.json. The mesh is used as given (not\n"
      "welded), so skin weights keep their vertex order.");
  static CommonOptions o;
  static DeformCli c;
  cmd->add_option("MESH", c.input, "Rest mesh (.vtp .ply .obj .stl)")->required();
  cmd->add_option("--deformer", c.deformer, "affine, noise or skin")->required();
  cmd->add_option("--skin", c.skin, "Skin file (JSON: bones, per-vertex weights, keyframes)");
  cmd->add_option("--frames", c.frames, "Number of frames (default 60)");
  cmd->add_option("--amplitude", c.amplitude,
                  "noise: peak displacement, fraction of the bounding-box diagonal (0.02)");
  cmd->add_option("--waves", c.waves, "noise: wavelengths per bounding-box diagonal (4)");
  cmd->add_option("--estimator", c.estimator,
                  "rusinkiewicz (default), batagelo, prantl3 or prantl2 (those with a prepared "
                  "path; the others are refused)");
  cmd->add_option("--ao-scale", o.ao_scale, "Ambient-occlusion radius (default 4 mean edges)");
  cmd->add_option("-o,--output", c.output, "Output folder (created if missing)")->required();
  add_common_options(*cmd, o, false);
  add_compress_option(*cmd, o);
  cmd->callback([] { run_deform(c, o); });
}

}  // namespace isocurv::app
