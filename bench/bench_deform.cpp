// Deforming-mesh benchmark (SEEDS-SPEC G-DEF1 (b), G-DEF2): per-frame curvature on a prepared
// topology against the cold call, and animation frames per second (deformer on the device, then
// curvature and its download) beside Griffin et al.'s Table 2 (GTX 480). Not a test: prints tables.
//
//   bench_deform [--quick] [--runs N]
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>

#include "bench/bench_util.h"
#include "core/cl_device.h"
#include "curvature/estimate.h"
#include "curvature/topology.h"
#include "datasets/field.h"
#include "datasets/sample.h"
#include "deform/affine.h"
#include "deform/skinning.h"
#include "mc/extract.h"
#include "test_meshes.h"

using namespace isocurv;

namespace {

// Prepared estimate (positions uploaded, or already resident) against the cold call.
void prepared_vs_cold(const std::string& name, const Mesh& mesh, int runs) {
  Device& dev = Device::default_device();
  curvature::Topology topo = curvature::prepare(mesh.triangles, mesh.vertex_count(), dev);
  curvature::CurvatureField a, b, c;
  curvature::upload_positions(mesh.positions, topo);
  const std::vector<double> t =
      bench::medians_ms({{[&] { curvature::estimate(mesh, dev, {}, a); }, runs},
                         {[&] { curvature::estimate(mesh.positions, topo, dev, {}, b); }, runs},
                         {[&] { curvature::estimate_resident(topo, dev, {}, c); }, runs}});
  std::printf("%-20s %9zu %9.2f %9.2f %9.2f %8.2f %8.2f\n", name.c_str(), mesh.vertex_count(), t[0],
              t[1], t[2], t[1] / t[0], t[2] / t[0]);
  // Where the time goes (queue drained after each step): what preparing saves is the first two.
  curvature::Timings ct, pt;
  curvature::estimate(mesh, dev, {}, a, &ct);
  curvature::estimate(mesh.positions, topo, dev, {}, b, &pt);
  for (const auto& [label, s] : {std::pair{"cold", ct}, std::pair{"prepared", pt}})
    std::printf(
        "  %-9s steps ms: adjacency %.2f upload %.2f normals+areas+boundary %.2f tensor %.2f "
        "directions %.2f derivative %.2f download %.2f\n",
        label, s.adjacency, s.upload, s.normals_areas, s.tensor, s.directions, s.derivative,
        s.download);
  std::fflush(stdout);
}

// Two bones split at z = 0 with a soft blend band; bone 1 swings 60 degrees about x over 1 s.
deform::Skin two_bones(const Mesh& m) {
  deform::Skin s;
  s.bone_names = {"root", "swing"};
  s.pivots = {{0, 0, 0}, {0, 0, 0}};
  for (const Vec3f& p : m.positions) {
    const float u = std::fmin(1.0f, std::fmax(0.0f, 0.5f + 2.0f * p[2]));
    s.bones.push_back({0, 1, 0, 0});
    s.weights.push_back({1 - u, u, 0, 0});
  }
  deform::Keyframe k0, k1;
  k0.time = 0, k1.time = 1;
  k0.pose.resize(2), k1.pose.resize(2);
  k1.pose[1].rotation = {std::cos(0.5236), std::sin(0.5236), 0, 0};
  s.keyframes = {k0, k1};
  return s;
}

void animation(const std::string& name, const Mesh& mesh, const char* griffin, int runs) {
  Device& dev = Device::default_device();
  const std::size_t nv = mesh.vertex_count();
  curvature::Topology topo = curvature::prepare(mesh.triangles, nv, dev);
  cl::Buffer rest(dev.context(), CL_MEM_READ_ONLY, nv * sizeof(Vec3f));
  dev.queue().enqueueWriteBuffer(rest, CL_TRUE, 0, nv * sizeof(Vec3f), mesh.positions.data());
  const deform::Skin skin = two_bones(mesh);
  deform::DeviceSkin dskin(dev, skin);
  curvature::CurvatureField out;
  int fa = 0, fs = 0;
  auto affine_frame = [&] {
    const std::array<double, 3> a = deform::ellipsoid_axes((fa++ % 60) / 60.0);
    deform::affine(dev, rest, nv, deform::scaling(a[0], a[1], a[2]), topo.positions());
    curvature::estimate_resident(topo, dev, {}, out);
  };
  auto skin_frame = [&] {
    dskin.apply(rest, deform::bone_matrices(skin, (fs++ % 60) / 59.0), topo.positions());
    curvature::estimate_resident(topo, dev, {}, out);
  };
  auto skin_only = [&] {
    dskin.apply(rest, deform::bone_matrices(skin, 0.5), topo.positions());
    dev.queue().finish();
  };
  const std::vector<double> t =
      bench::medians_ms({{affine_frame, runs}, {skin_frame, runs}, {skin_only, runs}});
  std::printf("%-20s %9zu %9.2f %8.1f %9.2f %8.1f %9.3f | %s\n", name.c_str(), nv, t[0],
              1000 / t[0], t[1], 1000 / t[1], t[2], griffin);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  bench::keep_freed_memory();
  bool quick = false;
  int runs = 9;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) {
      quick = true;
    } else if (!std::strcmp(argv[i], "--runs") && i + 1 < argc) {
      runs = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: bench_deform [--quick] [--runs N]\n");
      return 2;
    }
  }
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  Device& dev = Device::default_device();
  std::printf("device: %s; medians of %d runs; every time includes the field's download\n",
              dev.info().name.c_str(), runs);
  // Torus grids sized like Griffin's Table 2 models: horse 8,431, elephant 42,321, fairy 97,124.
  const Mesh horse = test::torus(0.6, 0.25, 93, 91).mesh;
  const Mesh elephant = test::torus(0.6, 0.25, 206, 205).mesh;
  const Mesh fairy = test::torus(0.6, 0.25, 312, 311).mesh;

  std::printf("\nper-frame curvature on a prepared topology vs the cold call (target <= 0.7)\n");
  std::printf("%-20s %9s %9s %9s %9s %8s %8s\n", "mesh", "vertices", "cold ms", "prep ms",
              "resid ms", "prep/c", "resid/c");
  prepared_vs_cold("torus (fairy-sized)", fairy, runs);
  if (!quick) {
    auto sphere = datasets::make_field("sphere");
    const Mesh s256 = mc::extract(datasets::sample(*sphere, 256), float(sphere->isovalue()), dev);
    prepared_vs_cold("sphere 256^3", s256, std::max(3, runs / 2));
  }

  std::printf("\nanimation: deformer on the device + curvature on the prepared topology\n");
  std::printf("%-20s %9s %9s %8s %9s %8s %9s | %s\n", "mesh", "vertices", "affine ms", "fps",
              "skin ms", "fps", "skin only", "Griffin GTX480, curvature frame (Table 2)");
  animation("torus (horse-sized)", horse, "horse skinned 8,431 v: 0.9 ms", runs);
  animation("torus (elephant)", elephant, "elephant skinned 42,321 v: 3.3 ms", runs);
  animation("torus (fairy-sized)", fairy, "fairy flipbook 97,124 v: 6.4 ms", runs);
  return 0;
}
