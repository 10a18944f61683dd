// Extraction benchmark: isocurv's device marching cubes (PoCL here) beside vtkFlyingEdges3D and
// openvdb::tools::volumeToMesh on the same volumes in the same run. Not a test: prints a table.
//
//   bench_extract [--quick] [--runs N] [--datasets DIR] [--only NAME_PART]
//   bench_extract --volume PATH [--iso V] [--runs N]   (any volume; iso: its suggested value)
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/global_control.h>
#include <vtkFlyingEdges3D.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>

#include <algorithm>
#include <cstring>
#include <optional>
#include <filesystem>
#include <iostream>

#include "bench/bench_util.h"
#include "core/cl_device.h"
#include "core/error.h"
#include "datasets/field.h"
#include "datasets/sample.h"
#include "mc/extract.h"
#include "volume/load.h"

using namespace isocurv;

namespace {

struct Case {
  std::string name;
  volume::Volume volume;
  float iso;
};

void run_case(const Case& c, int runs) {
  Device& dev = Device::default_device();
  const volume::Volume& v = c.volume;
  std::size_t ours_tris = 0;
  mc::ExtractTimings steps;
  auto ours = [&] { ours_tris = mc::extract(v, c.iso, dev).triangles.size(); };
  mc::Options no_snap;  // plain marching cubes, as the peers
  no_snap.snap = 0;
  auto ours_plain = [&] { mc::extract(v, c.iso, dev, no_snap); };
  auto image = bench::to_image(v);
  std::size_t fe_tris = 0;
  auto fe = [&] {
    vtkNew<vtkFlyingEdges3D> f;
    f->SetInputData(image);
    f->SetValue(0, c.iso);
    f->ComputeNormalsOff();
    f->ComputeScalarsOff();
    f->Update();
    fe_tris = f->GetOutput()->GetNumberOfPolys();
  };
  std::size_t vdb_tris = 0;
  auto vdb = [&] {
    std::vector<openvdb::Vec3s> pts;
    std::vector<openvdb::Vec3I> tris;
    std::vector<openvdb::Vec4I> quads;
    openvdb::tools::volumeToMesh(*v.grid, pts, tris, quads, double(c.iso));
    vdb_tris = tris.size() + 2 * quads.size();
  };
  const std::vector<double> t =
      bench::medians_ms({{ours, runs}, {fe, runs}, {vdb, std::max(1, runs / 2)}, {ours_plain, runs}});
  const double t_ours = t[0], t_fe = t[1], t_vdb = t[2];
  const double m_ours = bench::peak_extra_mib(ours), m_fe = bench::peak_extra_mib(fe), m_vdb = bench::peak_extra_mib(vdb);
  std::printf("%-26s %10zu %9.1f %8.1f %7.2f %9.1f %7.2f %8.1f %8.1f %8.1f %8.1f\n", c.name.c_str(), ours_tris, t_ours,
              t_fe, t_fe / t_ours, t_vdb, t_vdb / t_ours, ours_tris / t_ours / 1000.0, m_ours, m_fe, m_vdb);
  // The steps separated (the queue drained after each): medians over the runs, per step.
  std::vector<mc::ExtractTimings> per_run(std::max(1, runs));
  for (auto& r : per_run) mc::extract(v, c.iso, dev, {}, &r);
  auto median = [&](double mc::ExtractTimings::*field) {
    std::vector<double> t;
    for (const auto& r : per_run) t.push_back(r.*field);
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
  };
  steps = per_run.front();
  std::printf("%-26s   ours, %zu bricks, %zu seam vertices: prepare %.1f, select %.1f, gather %.1f, classify+scan "
              "%.1f, seams %.1f, sort %.1f, emit %.1f, read %.1f, snap %.1f ms (%zu vertices snapped, %zu merged); "
              "with snapping %.1f ms, without %.1f ms: snap share %.0f%%\n", "", steps.bricks, steps.seam_vertices,
              median(&mc::ExtractTimings::prepare),
              median(&mc::ExtractTimings::select), median(&mc::ExtractTimings::gather),
              median(&mc::ExtractTimings::classify), median(&mc::ExtractTimings::seams),
              median(&mc::ExtractTimings::sort), median(&mc::ExtractTimings::emit), median(&mc::ExtractTimings::read),
              median(&mc::ExtractTimings::snap), steps.snapped, steps.merged, t_ours, t[3],
              100.0 * std::max(0.0, t_ours - t[3]) / t_ours);
  (void)fe_tris;
  (void)vdb_tris;
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  bench::keep_freed_memory();
  bool quick = false;
  int runs = 5;
  std::string data = ISOCURV_SHARED_DATASETS;
  std::string only;  // run only the volumes whose name contains this
  std::string volume_path;  // --volume: only this file
  std::optional<float> iso;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) quick = true;
    else if (!std::strcmp(argv[i], "--runs") && i + 1 < argc) runs = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--datasets") && i + 1 < argc) data = argv[++i];
    else if (!std::strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
    else if (!std::strcmp(argv[i], "--volume") && i + 1 < argc) volume_path = argv[++i];
    else if (!std::strcmp(argv[i], "--iso") && i + 1 < argc) iso = std::strtof(argv[++i], nullptr);
    else {
      std::fprintf(stderr, "usage: bench_extract [--quick] [--runs N] [--datasets DIR] [--only NAME_PART] "
                           "| --volume PATH [--iso V] [--runs N]\n");
      return 2;
    }
  }
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  vtkSMPTools::Initialize(2);
  openvdb::initialize();
  std::printf("device: %s; VTK SMP backend: %s, 2 threads; medians of %d runs\n",
              Device::default_device().info().name.c_str(), vtkSMPTools::GetBackend(), runs);
  std::printf("%-26s %10s %9s %8s %7s %9s %7s %8s %8s %8s %8s\n", "volume", "triangles", "ours ms", "FE ms", "FE/ours",
              "VDB ms", "VDB/our", "ktri/ms", "MiB ours", "MiB FE", "MiB VDB");
  if (!volume_path.empty()) {
    try {
      volume::Volume v = volume::load(volume_path);
      const float value = iso ? *iso : float(v.stats.suggested_isovalue);
      run_case(Case{std::filesystem::path(volume_path).filename().string(), std::move(v), value}, runs);
      return 0;
    } catch (const Error& e) {
      std::fprintf(stderr, "bench_extract: %s\n", e.what());
      return 1;
    }
  }
  std::vector<int> sizes = quick ? std::vector<int>{128} : std::vector<int>{256, 512};
  for (int n : sizes)
    for (const char* name : {"sphere", "torus", "gyroid"}) {
      const std::string label = std::string(name) + " " + std::to_string(n) + "^3";
      if (label.find(only) == std::string::npos) continue;
      auto field = datasets::make_field(name);
      Case c{label, datasets::sample(*field, n), float(field->isovalue())};
      run_case(c, runs);
    }
  struct Real { const char* name; const char* file; float iso; };
  const Real reals[] = {{"lobster", "lobster/lobster_301x324x56_uint8.raw", 40},
                        {"LIDC2 CT", "lidc2_ct/LIDC2_256x256x133_uint8.raw.gz", 60},
                        {"frogtissue", "frogtissue/frogtissue.mhd", 0.5f},
                        {"octaflower 512 (aa)", "aa_octaflower/octa-flower17k-512-aa-l0_1.vol", 127.5f}};
  for (const Real& r : reals) {
    const std::string path = data + "/" + r.file;
    if (!std::filesystem::exists(path) || std::string(r.name).find(only) == std::string::npos) continue;
    if (quick && std::strcmp(r.name, "lobster") != 0) continue;
    try {
      volume::LoadOptions lo;
      if (std::strstr(r.file, "LIDC2")) { lo.raw.spacing = {1.40625, 1.40625, 2.5}; }
      if (std::strstr(r.file, "lobster")) { lo.raw.spacing = {1, 1, 1.4}; }
      Case c{r.name, volume::load(path, lo), r.iso};
      run_case(c, runs);
    } catch (const Error& e) {
      std::printf("%-26s skipped: %s\n", r.name, e.what());
    }
  }
  return 0;
}
