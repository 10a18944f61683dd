// Curvature benchmark: isocurv's OpenCL estimator (PoCL here) beside vtkCurvatures (mean and
// Gaussian) and the single-threaded double reference, on marching-cubes meshes of the datasets.
// Not a test: prints a table.
//
//   bench_curvature [--quick] [--runs N]
//   bench_curvature --volume-estimator [--quick] [--runs N]   (the sphere row, then the volume
//                                                              estimator's table only)
//   bench_curvature --volume PATH [--iso V] [--runs N]   (any volume; iso: its suggested value)
#include <tbb/global_control.h>
#include <vtkCurvatures.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <chrono>
#include <cstring>
#include <filesystem>

#include "bench/bench_util.h"
#include "core/cl_device.h"
#include "core/error.h"
#include "curvature/auto_scale.h"
#include "curvature/estimate.h"
#include "curvature/reference.h"
#include "curvature/volume_estimate.h"
#include "datasets/field.h"
#include "datasets/sample.h"
#include "io/polydata.h"
#include "mc/extract.h"
#include "volume/load.h"

using namespace isocurv;

namespace {

void run_case(const std::string& name, const Mesh& mesh, int runs, bool with_reference) {
  Device& dev = Device::default_device();
  curvature::Timings steps;
  auto ours = [&] { curvature::estimate(mesh, dev, {}, nullptr); };
  auto poly = io::to_polydata(mesh, nullptr);
  auto vtk = [&](int type) {
    vtkNew<vtkCurvatures> c;
    c->SetInputData(poly);
    c->SetCurvatureType(type);
    c->Update();
  };
  const std::vector<double> t = bench::medians_ms(
      {{ours, runs}, {[&] { vtk(VTK_CURVATURE_MEAN); }, runs}, {[&] { vtk(VTK_CURVATURE_GAUSS); }, runs}});
  const double t_ours = t[0], t_mean = t[1], t_gauss = t[2];
  curvature::estimate(mesh, dev, {}, &steps);  // step times (queue drained between steps)
  double t_ref = -1;
  if (with_reference) {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    auto t0 = std::chrono::steady_clock::now();
    curvature::estimate_reference(mesh);
    t_ref = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }
  const double mem = bench::peak_extra_mib(ours);
  std::printf("%-22s %9zu %8.1f %8.1f %8.1f %7.2f %9.0f %7.1f %7.0f | %6.1f %6.1f %6.1f %6.1f %6.1f\n", name.c_str(),
              mesh.positions.size(), t_ours, t_mean, t_gauss, (t_mean + t_gauss) / t_ours, t_ref,
              t_ref > 0 ? t_ref / t_ours : 0.0, mem * 1048576.0 / mesh.positions.size(),
              steps.adjacency + steps.upload, steps.normals_areas, steps.tensor, steps.directions, steps.derivative);
  std::fflush(stdout);
}

Mesh mesh_of(const volume::Volume& v, float iso) { return mc::extract(v, iso, Device::default_device()); }

// The volume estimator beside the mesh estimator and vtkCurvatures on one volume's surface: at
// the default per-vertex scale (its pilot in voxels beside it) and at one voxel.
void run_volume_case(const std::string& name, const volume::Volume& v, float iso, int runs) {
  Device& dev = Device::default_device();
  const Mesh mesh = mesh_of(v, iso);
  const curvature::ScaleChoice choice = curvature::auto_scale(v, mesh, iso);
  const float ao = 1.0f;
  curvature::VolumeEstimateStats stats;
  auto mesh_estimator = [&] { curvature::estimate(mesh, dev, {}, nullptr); };
  auto at = [&](double sigma) {
    curvature::VolumeOptions o = curvature::fixed_scale(sigma, ao);
    o.point = curvature::VolumePoint::vertex;
    return [&, o] { curvature::volume_estimate(mesh, v, iso, o, dev, &stats); };
  };
  // The default: the per-vertex scale (curvature/adaptive_scale.h), as `curvature` runs it.
  curvature::VolumeOptions defaults;
  defaults.sigma = choice.scale;
  defaults.ao_scale = ao;
  defaults.adaptive = choice.model;
  defaults.point = curvature::resolved_point(curvature::VolumePoint::automatic, v);
  auto per_vertex = [&] { curvature::volume_estimate(mesh, v, iso, defaults, dev, &stats); };
  auto poly = io::to_polydata(mesh, nullptr);
  auto vtk = [&] {
    for (int type : {VTK_CURVATURE_MEAN, VTK_CURVATURE_GAUSS}) {
      vtkNew<vtkCurvatures> c;
      c->SetInputData(poly);
      c->SetCurvatureType(type);
      c->Update();
    }
  };
  const std::vector<double> t = bench::medians_ms(
      {{mesh_estimator, runs}, {per_vertex, runs}, {at(choice.voxel), runs}, {vtk, runs}});
  per_vertex();
  const double mem = bench::peak_extra_mib(per_vertex);
  const curvature::VolumeStepTimes& st = stats.steps;
  std::printf(
      "%-26s %9zu %8.1f %9.1f (%4.2f vox, %6zu finer) %8.1f %8.1f %7.2f %7.2f %7.0f | %5.1f "
      "%5.1f %5.1f %5.1f %5.1f\n",
      name.c_str(), mesh.positions.size(), t[0], t[1], choice.scale / choice.voxel,
      stats.finer_scale, t[2], t[3], t[1] / t[0], t[3] / t[1],
      mem * 1048576.0 / mesh.positions.size(), st.plan, st.gather, st.smooth, st.vertices,
      st.finish);
  std::fflush(stdout);
}

void volume_estimator_table(int runs, bool quick) {
  std::printf(
      "\nvolume estimator (curvature::volume_estimate) beside the mesh estimator and "
      "vtkCurvatures (H + K), same surface; medians of %d runs\n",
      runs);
  std::printf("%-26s %9s %8s %9s %24s %8s %8s %7s %7s %7s | %5s %5s %5s %5s %5s\n", "volume",
              "vertices", "mesh ms", "auto ms", "", "1 vox ms", "VTK ms", "auto/mesh", "VTK/auto",
              "B/vert", "plan", "gathr", "pass", "verts", "host");
  auto sphere = datasets::make_field("sphere");
  run_volume_case("sphere float 128^3", datasets::sample(*sphere, 128), float(sphere->isovalue()),
                  runs);
  if (quick) return;
  const std::string lobster = std::string(ISOCURV_SHARED_DATASETS) + "/lobster/lobster.vol";
  if (std::filesystem::exists(lobster)) {
    const volume::Volume v = volume::load(lobster);
    run_volume_case("lobster uint8 (CT)", v, float(v.stats.suggested_isovalue), runs);
  }
  auto gyroid = datasets::make_field("gyroid");
  run_volume_case("gyroid float 256^3", datasets::sample(*gyroid, 256), float(gyroid->isovalue()),
                  runs);
}

}  // namespace

int main(int argc, char** argv) {
  bench::keep_freed_memory();
  bool quick = false, volume_only = false;
  int runs = 5;
  std::string volume_path;
  float iso = 0;
  bool iso_given = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) quick = true;
    else if (!std::strcmp(argv[i], "--volume-estimator"))
      volume_only = true;
    else if (!std::strcmp(argv[i], "--runs") && i + 1 < argc) runs = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--volume") && i + 1 < argc) volume_path = argv[++i];
    else if (!std::strcmp(argv[i], "--iso") && i + 1 < argc) iso = std::strtof(argv[++i], nullptr), iso_given = true;
    else {
      std::fprintf(stderr,
                   "usage: bench_curvature [--quick] [--volume-estimator] [--runs N] | --volume "
                   "PATH [--iso V] [--runs N]\n");
      return 2;
    }
  }
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  openvdb::initialize();
  std::printf("device: %s; vtkCurvatures is serial; the reference runs on one thread; medians of %d runs\n",
              Device::default_device().info().name.c_str(), runs);
  std::printf("%-22s %9s %8s %8s %8s %7s %9s %7s %7s | %6s %6s %6s %6s %6s\n", "mesh", "vertices", "ours ms",
              "VTK H", "VTK K", "VTK/us", "ref ms", "ref/us", "B/vert", "setup", "n+area", "tensor", "dirs", "deriv");
  if (!volume_path.empty()) {
    try {
      const volume::Volume v = volume::load(volume_path);
      const float value = iso_given ? iso : float(v.stats.suggested_isovalue);
      run_case(std::filesystem::path(volume_path).filename().string(), mesh_of(v, value), runs, true);
      run_volume_case(std::filesystem::path(volume_path).filename().string(), v, value, runs);
      return 0;
    } catch (const Error& e) {
      std::fprintf(stderr, "bench_curvature: %s\n", e.what());
      return 1;
    }
  }
  auto sphere = datasets::make_field("sphere");
  run_case("sphere 256^3", mesh_of(datasets::sample(*sphere, 256), float(sphere->isovalue())), runs, true);
  if (volume_only) {
    volume_estimator_table(runs, quick);
    return 0;
  }
  if (quick) {
    volume_estimator_table(runs, quick);
    return 0;
  }
  const std::string flower = std::string(ISOCURV_SHARED_DATASETS) + "/aa_octaflower/octa-flower17k-512-aa-l0_1.vol";
  if (std::filesystem::exists(flower))
    run_case("octaflower 512 (aa)", mesh_of(volume::load(flower), 127.5f), runs, true);
  auto gyroid = datasets::make_field("gyroid");
  run_case("gyroid 320^3", mesh_of(datasets::sample(*gyroid, 320), float(gyroid->isovalue())), runs, true);
  run_case("gyroid 512^3", mesh_of(datasets::sample(*gyroid, 512), float(gyroid->isovalue())), std::max(1, runs / 2), true);
  std::printf("Griffin et al. (GPU, 2012): 2.7M vertices in 26.7 ms\n");
  volume_estimator_table(runs, quick);
  return 0;
}
