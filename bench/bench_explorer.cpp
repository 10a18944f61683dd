// Explorer benchmark: the update `isocurv view` runs when the isovalue slider moves
// (mc::Mesher::extract at the new isovalue + curvature::estimate, as app/cmd_view.cpp's callback,
// then the scene's set_surface + an offscreen re-render as viz's explorer does), swept over 20
// isovalues on 128^3 volumes. Beside it, from the same run, VTK's equivalent update on the same
// dense image: vtkFlyingEdges3D + vtkCurvatures (mean) + vtkCurvatures (Gaussian), then a re-render
// of the result. Target: at least 10 updates per second. With the feature lines on (the explorer's
// 'l': contours and suggestive contours, lines::extract + join_segments), the update with lines
// after an isovalue change, and the lines alone after a camera move (20 azimuth steps around the
// middle isovalue's surface, the mesh already on the device). Then the explorer's screen-space
// mode ('x'), where the slider re-casts instead: screen::ray_cast + the 2-edge screen::estimate at
// the scene's surface box (800x600 window), then set_image + an offscreen re-render, and the
// same at half resolution (what a camera drag shows when a full image is slow). Not a test:
// prints tables.
//
//   bench_explorer [--passes N] [--isovalues N] [--no-render] [--size WxH] [--datasets DIR]
#include <tbb/global_control.h>
#include <vtkActor.h>
#include <vtkCurvatures.h>
#include <vtkFlyingEdges3D.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSMPTools.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iostream>
#include <optional>

#include "bench/bench_util.h"
#include "core/cl_device.h"
#include "core/error.h"
#include "curvature/ao_scale.h"
#include "curvature/estimate.h"
#include "curvature/estimator.h"
#include "datasets/field.h"
#include "datasets/sample.h"
#include "lines/extract.h"
#include "lines/polylines.h"
#include "mc/extract.h"
#include "screen/estimate.h"
#include "screen/image_files.h"
#include "screen/ray_cast.h"
#include "viz/curvature_scene.h"
#include "viz/headless_display.h"
#include "volume/dense_field.h"
#include "volume/load.h"

using namespace isocurv;

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct Config {
  int passes = 3;       ///< timed sweeps; each isovalue's time is its median over the passes
  int isovalues = 20;
  bool render = true;
  int width = 800, height = 600;
  std::string data = ISOCURV_SHARED_DATASETS;
};

/// Median and max over the isovalues of each isovalue's median over the passes.
struct Summary {
  double median = 0, max = 0;
};

Summary summarize(const std::vector<std::vector<double>>& per_iso) {
  std::vector<double> medians;
  for (auto t : per_iso) {
    if (t.empty()) continue;
    std::sort(t.begin(), t.end());
    medians.push_back(t[t.size() / 2]);
  }
  if (medians.empty()) return {};
  std::sort(medians.begin(), medians.end());
  return {medians[medians.size() / 2], medians.back()};
}

/// One offscreen window per side, kept for the whole run as the explorer keeps its own.
struct Windows {
  vtkNew<vtkRenderWindow> ours, vtk;
  viz::CurvatureScene scene;
  vtkNew<vtkRenderer> vtk_renderer;
  vtkNew<vtkPolyDataMapper> vtk_mapper;
  vtkNew<vtkActor> vtk_actor;

  explicit Windows(const Config& c) {
    for (vtkRenderWindow* w : {ours.Get(), vtk.Get()}) {
      w->SetOffScreenRendering(1);
      w->SetSize(c.width, c.height);
    }
    viz::check_opengl(ours);
    scene.attach(ours);
    scene.set_size(c.width, c.height);  // the layout of the window's size, as the explorer's
    vtk_mapper->SetScalarModeToUsePointData();
    vtk_mapper->ScalarVisibilityOn();
    vtk_actor->SetMapper(vtk_mapper);
    vtk_renderer->AddActor(vtk_actor);
    vtk->AddRenderer(vtk_renderer);
  }
};

struct Row {
  std::string name;
  Summary ours, ours_render, vtk, vtk_render;
  Summary ours_lines, camera_lines;  // update + lines; lines alone after a camera move
  Summary screen, screen_render, screen_half;  // screen-space mode: cast + estimate (+ show)
  Summary dflt;  // extract + the default estimator on volume input (the volume estimator)
  double coverage = 0;                         // of the screen image, middle isovalue
  double setup_ms = 0;
  std::size_t tri_median = 0, tri_max = 0;
};

void print_header(bool render, int isovalues) {
  const std::string first = "volume (" + std::to_string(isovalues) + " isovalues)";
  std::printf("%-24s %8s %9s %8s %8s %7s", first.c_str(), "tri med", "tri max", "ours med",
              "ours max", "ours/s");
  if (render) std::printf(" %8s %8s %7s", "+rnd med", "+rnd max", "+rnd/s");
  std::printf(" %8s %8s %7s", "VTK med", "VTK max", "VTK/s");
  if (render) std::printf(" %8s %7s", "+rnd med", "+rnd/s");
  std::printf(" %8s %7s", "VTK/ours", "10/s");
  if (render) std::printf(" %8s", "10/s+rnd");
  std::printf(" | %8s %7s %8s %7s", "+lin med", "+lin/s", "cam med", "cam/s");
  std::printf("\n");
}

void print_row(const Row& r, bool render) {
  auto ups = [](double ms) { return ms > 0 ? 1000.0 / ms : 0.0; };
  std::printf("%-24s %8zu %9zu %8.1f %8.1f %7.1f", r.name.c_str(), r.tri_median, r.tri_max, r.ours.median, r.ours.max,
              ups(r.ours.median));
  if (render)
    std::printf(" %8.1f %8.1f %7.1f", r.ours_render.median, r.ours_render.max, ups(r.ours_render.median));
  std::printf(" %8.1f %8.1f %7.1f", r.vtk.median, r.vtk.max, ups(r.vtk.median));
  if (render) std::printf(" %8.1f %7.1f", r.vtk_render.median, ups(r.vtk_render.median));
  // The target (100 ms a step), judged on the update alone (what cmd_view reports as update_ms) and
  // with the re-render (what the user waits for).
  auto verdict = [](const Summary& s) { return s.max <= 100.0 ? "met" : s.median <= 100.0 ? "median" : "MISSED"; };
  std::printf(" %8.2f %7s", r.ours.median > 0 ? r.vtk.median / r.ours.median : 0.0, verdict(r.ours));
  if (render) std::printf(" %8s", verdict(r.ours_render));
  std::printf(" | %8.1f %7.1f %8.1f %7.1f", r.ours_lines.median, ups(r.ours_lines.median), r.camera_lines.median,
              ups(r.camera_lines.median));
  std::printf("\n");
  std::fflush(stdout);
}

Row run_volume(const std::string& name, const volume::Volume& v, const Config& c, Windows* win) {
  Device& dev = Device::default_device();
  Row row;
  row.name = name;
  const double lo = v.stats.min, hi = v.stats.max;
  std::vector<float> isos;
  for (int i = 0; i < c.isovalues; ++i)  // across the slider's range, ends excluded (no surface there)
    isos.push_back(static_cast<float>(lo + (hi - lo) * (0.05 + 0.9 * i / std::max(1, c.isovalues - 1))));

  auto t0 = Clock::now();
  mc::Mesher mesher(v, dev);
  row.setup_ms = ms_since(t0);
  auto image = bench::to_image(v);

  // Our update: extract + curvature (what cmd_view's callback does), optionally + scene re-render.
  std::vector<std::size_t> tris(isos.size());
  auto ours_update = [&](std::size_t i, bool render) {
    Mesh mesh = mesher.extract(isos[i]);
    curvature::Options co;
    co.ao_scale = curvature::default_ao_scale(mesh);
    curvature::CurvatureField field = curvature::estimate(mesh, dev, co);
    tris[i] = mesh.triangles.size();
    if (render && win) {
      win->scene.set_surface(mesh, field);
      win->ours->Render();
    }
  };
  // VTK's: flying edges + mean and Gaussian curvature, optionally + re-render coloured by H.
  auto vtk_update = [&](std::size_t i, bool render) {
    vtkNew<vtkFlyingEdges3D> fe;
    fe->SetInputData(image);
    fe->SetValue(0, isos[i]);
    fe->ComputeNormalsOff();
    fe->ComputeScalarsOff();
    vtkNew<vtkCurvatures> mean;
    mean->SetInputConnection(fe->GetOutputPort());
    mean->SetCurvatureTypeToMean();
    vtkNew<vtkCurvatures> gauss;
    gauss->SetInputConnection(mean->GetOutputPort());
    gauss->SetCurvatureTypeToGaussian();
    gauss->Update();
    if (render && win) {
      vtkPolyData* out = gauss->GetOutput();
      out->GetPointData()->SetActiveScalars("Mean_Curvature");
      win->vtk_mapper->SetInputData(out);
      win->vtk_mapper->SetScalarRange(-10, 10);
      win->vtk_renderer->ResetCamera();
      win->vtk->Render();
    }
  };

  auto sweep = [&](const std::function<void(std::size_t)>& f) {
    std::vector<std::vector<double>> per_iso(isos.size());
    for (std::size_t i = 0; i < isos.size(); ++i) f(i);  // warm-up pass (program builds, buffers)
    for (int p = 0; p < c.passes; ++p)
      for (std::size_t i = 0; i < isos.size(); ++i) {
        const auto t = Clock::now();
        f(i);
        per_iso[i].push_back(ms_since(t));
      }
    return summarize(per_iso);
  };
  row.ours = sweep([&](std::size_t i) { ours_update(i, false); });
  // The explorer's default on volume input: the volume estimator at its automatic per-vertex
  // scale (curvature::estimate_field, as app/cmd_view.cpp's callback through estimate_curvature),
  // its pyramid kept between isovalues (volume::PyramidLease).
  row.dflt = sweep([&](std::size_t i) {
    Mesh mesh = mesher.extract(isos[i]);
    curvature::Options vo;
    vo.estimator = curvature::Estimator::volume;
    vo.ao_scale = curvature::default_ao_scale(mesh);
    curvature::estimate_field(mesh, {&v, isos[i]}, &dev, vo);
  });
  if (c.render && win) {
    win->scene.frame_camera();
    row.ours_render = sweep([&](std::size_t i) { ours_update(i, true); });
  }
  // With the lines: the camera is the explorer's first (fit_camera, iso view) for each surface.
  lines::Options line_opts;  // contours and suggestive contours, the explorer's default
  auto bounds_of = [](const Mesh& m) {
    std::array<double, 6> b = {1e30, -1e30, 1e30, -1e30, 1e30, -1e30};
    for (const Vec3f& p : m.positions)
      for (int k = 0; k < 3; ++k) b[2 * k] = std::min(b[2 * k], double(p[k])), b[2 * k + 1] = std::max(b[2 * k + 1], double(p[k]));
    return b;
  };
  const double aspect = double(c.width) / double(c.height);
  row.ours_lines = sweep([&](std::size_t i) {
    Mesh mesh = mesher.extract(isos[i]);
    curvature::Options co;
    co.ao_scale = curvature::default_ao_scale(mesh);
    curvature::CurvatureField field = curvature::estimate(mesh, dev, co);
    const Camera cam = fit_camera(bounds_of(mesh), ViewSpec{}, aspect);
    lines::join_segments(lines::extract(mesh, field, cam, line_opts, dev));
  });
  {
    const Mesh mesh = mesher.extract(isos[isos.size() / 2]);
    curvature::Options co;
    co.ao_scale = curvature::default_ao_scale(mesh);
    const curvature::CurvatureField field = curvature::estimate(mesh, dev, co);
    const std::array<double, 6> box = bounds_of(mesh);
    lines::extract(mesh, field, fit_camera(box, ViewSpec{}, aspect), line_opts, dev);  // uploads the mesh
    row.camera_lines = sweep([&](std::size_t i) {
      ViewSpec turned;
      turned.azimuth_deg = 360.0 * double(i) / double(isos.size());
      const Camera cam = fit_camera(box, turned, aspect);
      lines::join_segments(lines::extract(mesh, field, cam, line_opts, dev, nullptr, false));
    });
  }
  // Screen-space mode: the camera the explorer starts with (the middle isovalue's surface box).
  {
    const volume::DenseField field(v);
    std::array<double, 6> box = field.bounds;
    field.surface_bounds(isos[isos.size() / 2], box);
    int w = c.width, h = c.height;
    if (win) {
      win->scene.set_image_mode(false);
      viz::RenderOptions o = win->scene.options();
      o.color = "H";
      win->scene.set_options(o);
      win->scene.set_image_mode(true);
      const viz::PixelBox& b = win->scene.layout().surface;
      w = b.x1 - b.x0, h = b.y1 - b.y0;
    }
    const Camera cam = fit_camera(box, ViewSpec{}, double(w) / h);
    auto screen_update = [&](std::size_t i, int scale, bool render) {
      const int sw = (w + scale - 1) / scale, sh = (h + scale - 1) / scale;
      const screen::GBuffer g =
          screen::ray_cast(field, isos[i], screen::view_frame(cam, sw, sh), dev);
      viz::ScreenImage img = screen::explorer_image(g, screen::estimate(g, dev), true);
      if (i == isos.size() / 2 && scale == 1)
        row.coverage = double(img.valid_count()) / img.pixels();
      if (render && win) {
        win->scene.set_image(img, scale);
        win->ours->Render();
      }
    };
    row.screen = sweep([&](std::size_t i) { screen_update(i, 1, false); });
    if (c.render && win) {
      viz::apply_camera(win->scene.renderer(), cam);
      row.screen_render = sweep([&](std::size_t i) { screen_update(i, 1, true); });
      row.screen_half = sweep([&](std::size_t i) { screen_update(i, 2, true); });
      win->scene.set_image_mode(false);
    }
  }
  row.vtk = sweep([&](std::size_t i) { vtk_update(i, false); });
  if (c.render && win) row.vtk_render = sweep([&](std::size_t i) { vtk_update(i, true); });
  std::vector<std::size_t> sorted = tris;
  std::sort(sorted.begin(), sorted.end());
  row.tri_median = sorted[sorted.size() / 2];
  row.tri_max = sorted.back();
  return row;
}

int usage() {
  std::fprintf(stderr, "usage: bench_explorer [--passes N] [--isovalues N] [--no-render] [--size WxH] [--datasets DIR]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  bench::keep_freed_memory();
  Config c;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--passes") && i + 1 < argc) c.passes = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--isovalues") && i + 1 < argc) c.isovalues = std::max(2, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--no-render")) c.render = false;
    else if (!std::strcmp(argv[i], "--size") && i + 1 < argc) {
      if (std::sscanf(argv[++i], "%dx%d", &c.width, &c.height) != 2 || c.width < 16 || c.height < 16) return usage();
    } else if (!std::strcmp(argv[i], "--datasets") && i + 1 < argc) c.data = argv[++i];
    else return usage();
  }
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  vtkSMPTools::Initialize(2);
  openvdb::initialize();

  std::optional<Windows> windows;
  if (c.render) {
    try {
      viz::ensure_display();
      windows.emplace(c);
    } catch (const Error& e) {
      std::printf("rendering skipped: %s\n", e.what());
      c.render = false;
    }
  }
  std::printf("device: %s; VTK SMP backend: %s, 2 threads; %d isovalues from 5%% to 95%% of each volume's range;\n"
              "per isovalue the median of %d passes (after a warm-up pass); columns give the median and max over the\n"
              "isovalues, in ms, and updates per second from the median. ours = Mesher::extract + curvature::estimate\n"
              "(all arrays, AO); VTK = vtkFlyingEdges3D + vtkCurvatures mean + Gaussian.%s Target: >= 10 updates/s.\n\n",
              Device::default_device().info().name.c_str(), vtkSMPTools::GetBackend(), c.isovalues, c.passes,
              c.render ? (" +rnd = also the offscreen re-render (" + std::to_string(c.width) + "x" +
                          std::to_string(c.height) + ", set_surface + Render).").c_str()
                       : "");
  print_header(c.render, c.isovalues);
  std::vector<Row> rows;
  for (const char* name : {"torus", "gyroid", "buckyball"}) {
    auto field = datasets::make_field(name);
    const volume::Volume v = datasets::sample(*field, 128);
    rows.push_back(run_volume(std::string(name) + " 128^3", v, c, windows ? &*windows : nullptr));
    print_row(rows.back(), c.render);
  }
  struct Real { const char* name; const char* file; };
  for (const Real& r : {Real{"octaflower 128 (aa)", "aa_octaflower/octa-flower17k-128-aa-l0_1.vol"},
                        Real{"bunny 128 (vg)", "vg_bunny/bunny-128.vol"}}) {
    const std::string path = c.data + "/" + r.file;
    if (!std::filesystem::exists(path)) {
      std::printf("%-24s skipped: %s not found\n", r.name, path.c_str());
      continue;
    }
    try {
      const volume::Volume v = volume::load(path);
      rows.push_back(run_volume(r.name, v, c, windows ? &*windows : nullptr));
      print_row(rows.back(), c.render);
    } catch (const Error& e) {
      std::printf("%-24s skipped: %s\n", r.name, e.what());
    }
  }
  std::printf("\n10/s (update alone) and 10/s+rnd (with the re-render): met = every isovalue within 100 ms; median = the\n"
              "median within 100 ms but not the slowest isovalue; MISSED = the median above 100 ms.\n"
              "VTK/ours = VTK's median update over ours (no render; above 1 means ours is faster).\n"
              "+lin = ours + contours and suggestive contours (lines::extract + join_segments, no render);\n"
              "cam = those lines alone after a camera move (20 azimuths round the middle isovalue's surface).\n");
  std::printf(
      "\nScreen-space mode (the explorer's 'x'): the slider re-casts the volume (screen::ray_cast) "
      "and runs the\n"
      "2-edge estimate at the scene's surface box, then set_image + re-render; 1/2 = the same at "
      "half resolution\n"
      "(a camera drag when a full image is slow). Beside it, from the table above: extract + "
      "curvature + re-render.\n");
  std::printf("%-24s %7s %8s %7s %8s %7s %8s %7s | %8s %7s %7s\n", "volume", "cover%", "scr med",
              "scr/s", "+rnd med", "+rnd/s", "1/2 med", "1/2/s", "mesh+rnd", "mesh/s", "10/s");
  for (const Row& r : rows) {
    auto ups = [](double ms) { return ms > 0 ? 1000.0 / ms : 0.0; };
    const Summary& shown = c.render ? r.screen_render : r.screen;
    std::printf("%-24s %7.1f %8.1f %7.1f %8.1f %7.1f %8.1f %7.1f | %8.1f %7.1f %7s\n",
                r.name.c_str(), 100 * r.coverage, r.screen.median, ups(r.screen.median),
                r.screen_render.median, ups(r.screen_render.median), r.screen_half.median,
                ups(r.screen_half.median), c.render ? r.ours_render.median : r.ours.median,
                ups(c.render ? r.ours_render.median : r.ours.median),
                shown.max <= 100.0      ? "met"
                : shown.median <= 100.0 ? "median"
                                        : "MISSED");
  }
  std::printf(
      "\nThe default estimator (what the explorer runs on volume input: the volume estimator at its "
      "automatic\nper-vertex scale, the pyramid kept between isovalues), extract + estimate_field, "
      "no render; beside it the mesh\nestimator's update from the first table.\n");
  std::printf("%-24s %8s %8s %7s | %8s %7s %7s\n", "volume", "dflt med", "dflt max", "dflt/s",
              "mesh med", "mesh/s", "10/s");
  for (const Row& r : rows) {
    auto ups = [](double ms) { return ms > 0 ? 1000.0 / ms : 0.0; };
    std::printf("%-24s %8.1f %8.1f %7.1f | %8.1f %7.1f %7s\n", r.name.c_str(), r.dflt.median,
                r.dflt.max, ups(r.dflt.median), r.ours.median, ups(r.ours.median),
                r.dflt.max <= 100.0      ? "met"
                : r.dflt.median <= 100.0 ? "median"
                                         : "MISSED");
  }
  std::printf("Mesher setup (once per volume, before the first update), ms:");
  for (const Row& r : rows) std::printf("  %s %.0f", r.name.c_str(), r.setup_ms);
  std::printf("\n");
  return 0;
}
