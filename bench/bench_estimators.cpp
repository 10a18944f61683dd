// Every mesh estimator on the seed papers' protocols, beside the figures of SEEDS-SPEC Appendix A
// (an independent double-precision computation) and the papers' own; then marching-cubes meshes
// with volume normals; then the kernel paths' speed beside the Rusinkiewicz path and vtkCurvatures.
// Not a test: prints tables.
//
//   bench_estimators [--quick]      (--quick: smaller speed meshes, no 60k height fields)
#include <vtkCurvatures.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/cl_device.h"
#include "curvature/batagelo.h"
#include "curvature/cubic_fit.h"
#include "curvature/estimate.h"
#include "curvature/face_average_normals.h"
#include "curvature/meyer.h"
#include "curvature/normal_sampling.h"
#include "curvature/prantl.h"
#include "curvature/quadric_fit.h"
#include "curvature/reference.h"
#include "datasets/exact_curvature.h"
#include "datasets/field.h"
#include "datasets/sample.h"
#include "io/polydata.h"
#include "mc/extract.h"
#include "tests/curvature/estimator_protocols.h"
#include "volume/gradient_normals.h"

using namespace isocurv;
using curvature::CurvatureField;

namespace {

using Fn = std::function<CurvatureField(const Mesh&, const curvature::Options&)>;
struct Estimator {
  const char* name;
  Fn fn;
};

const std::vector<Estimator>& estimators() {
  static const std::vector<Estimator> e = {
      {"rusinkiewicz",
       [](const Mesh& m, const curvature::Options& o) { return curvature::estimate_reference(m, o); }},
      {"batagelo", curvature::estimate_batagelo_reference},
      {"quadric", curvature::estimate_quadric_fit_reference},
      {"cubic", curvature::estimate_cubic_fit_reference},
      {"sampling", curvature::estimate_normal_sampling_reference},
      {"prantl3",
       [](const Mesh& m, const curvature::Options& o) {
         return curvature::estimate_prantl_reference(m, o, 3);
       }},
      {"prantl2",
       [](const Mesh& m, const curvature::Options& o) {
         return curvature::estimate_prantl_reference(m, o, 2);
       }},
      {"meyer", curvature::estimate_meyer_reference}};
  return e;
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void header(const char* title) {
  std::printf("\n%s\n%-8s", title, "");
  for (const Estimator& e : estimators()) std::printf(" %13s", e.name);
  std::printf("\n");
}

// A1/A2: the torus protocols. Ours, then Appendix A in brackets (no Meyer figure there).
void torus_protocols() {
  header("Batagelo Fig. 2: torus 60x24, jittered grid, unit-face-average normals; RMS K error "
         "[Appendix A1]");
  const double jit[] = {0, 0.1, 0.2, 0.3, 0.4};
  const double a1[5][7] = {{0.0418, 0.0676, 0.0516, 0.0767, 0.0029, 0.0426, 0.0634},
                           {0.0964, 0.1190, 0.1479, 0.1263, 0.1041, 0.0959, 0.1050},
                           {0.1969, 0.2286, 0.4185, 0.3262, 0.3806, 0.1892, 0.1903},
                           {0.3374, 0.3792, 0.7456, 0.8231, 0.9166, 0.3126, 0.3103},
                           {0.6774, 0.7882, 1.5909, 3.3996, 2.8170, 0.7189, 0.6801}};
  for (int k = 0; k < 5; ++k) {
    const test::Torus t = test::torus(1, 0.4, 60, 24, jit[k]);
    const std::vector<Vec3f> n = curvature::face_average_normals(t.mesh);
    curvature::Options o;
    o.vertex_normals = &n;
    std::printf("j=%-6.1f", jit[k]);
    for (std::size_t e = 0; e < estimators().size(); ++e) {
      const double err = test::torus_rms_K(estimators()[e].fn(t.mesh, o), t);
      if (e < 7)
        std::printf(" %6.4f[%.4f]", err, a1[k][e]);
      else
        std::printf(" %6.4f       ", err);
    }
    std::printf("\n");
  }
  header("Batagelo Fig. 3: torus 60x24 displaced along the normal by U(-d,d) r, exact normals; "
         "RMS K [Appendix A2]");
  const double ds[] = {0, 0.005, 0.01, 0.02, 0.04};
  const double a2[5][7] = {{0.0387, 0.0644, 0.0643, 0.0800, 0.0064, 0.0396, 0.0621},
                           {0.0402, 0.0645, 0.8975, 0.0800, 0.8841, 0.0412, 0.0631},
                           {0.0448, 0.0647, 1.8068, 0.0803, 1.7771, 0.0459, 0.0663},
                           {0.0641, 0.0656, 3.7356, 0.0813, 3.6211, 0.0652, 0.0805},
                           {0.1391, 0.0691, 8.3986, 0.0856, 7.6757, 0.1389, 0.1461}};
  for (int k = 0; k < 5; ++k) {
    const test::Torus t = test::displaced_torus(1, 0.4, 60, 24, ds[k]);
    const std::vector<Vec3f> n = test::exact_normals(t);
    curvature::Options o;
    o.vertex_normals = &n;
    std::printf("d=%-6.3f", ds[k]);
    for (std::size_t e = 0; e < estimators().size(); ++e) {
      const double err = test::torus_rms_K(estimators()[e].fn(t.mesh, o), t);
      if (e < 7)
        std::printf(" %6.4f[%.4f]", err, a2[k][e]);
      else
        std::printf(" %6.4f       ", err);
    }
    std::printf("\n");
  }
}

// A3: C122 along the tube.
void derivative_protocol() {
  std::printf("\nDerivative: torus(1, 0.4), exact normals, relative RMS of C122 against dk2/ds "
              "[Appendix A3: corrected / Rusinkiewicz]\n");
  const double a3[3][2] = {{0.0246, 0.0284}, {0.0063, 0.0072}, {0.0016, 0.0018}};
  for (int l = 0; l < 3; ++l) {
    const test::Torus t = test::torus(1, 0.4, 60 << l, 24 << l);
    const std::vector<Vec3f> n = test::exact_normals(t);
    curvature::Options o;
    o.vertex_normals = &n;
    double err[2];
    const CurvatureField f[2] = {curvature::estimate_batagelo_reference(t.mesh, o),
                                 curvature::estimate_reference(t.mesh, o)};
    for (int k = 0; k < 2; ++k) {
      std::vector<double> got, want;
      for (std::size_t i = 0; i < f[k].size(); ++i) {
        const Eigen::Vector3d d(f[k].dir1[i][0], f[k].dir1[i][1], f[k].dir1[i][2]);
        got.push_back((d.dot(t.tube_dir(i)) < 0 ? -1 : 1) * f[k].dcurv[i][2]);
        want.push_back(t.dk2_along_tube(i));
      }
      err[k] = test::relative_rms(got, want);
    }
    std::printf("  %3dx%-3d batagelo %.4f [%.4f]  rusinkiewicz %.4f [%.4f]\n", 60 << l, 24 << l,
                err[0], a3[l][0], err[1], a3[l][1]);
  }
}

// A4: f1/f2 from random points, exact normals, MSE over |x|, |y| < 9.
void heightfield_protocol(bool quick) {
  std::printf("\nPrantl 4.1: f1/f2 Delaunay of N random points, exact normals, MSE of H / K "
              "[Appendix A4]\n");
  struct Row {
    const char* f;
    int n;
    double a[6];  // P3 H, P3 K, P2 H, P2 K, Rusinkiewicz H, K
  };
  const Row rows[] = {
      {"f1", 1000, {1.72e-2, 2.58e-3, 1.72e-2, 2.57e-3, 1.59e-2, 2.83e-3}},
      {"f1", 4000, {5.55e-3, 4.32e-3, 5.55e-3, 4.35e-3, 5.01e-3, 3.73e-3}},
      {"f1", 15000, {1.34e-3, 1.75e-3, 1.34e-3, 1.77e-3, 1.21e-3, 1.56e-3}},
      {"f1", 60000, {3.88e-4, 9.56e-4, 3.88e-4, 9.58e-4, 3.47e-4, 8.59e-4}},
      {"f2", 1000, {8.00e-3, 6.53e-3, 8.00e-3, 6.56e-3, 7.68e-3, 6.34e-3}},
      {"f2", 4000, {1.87e-3, 1.56e-3, 1.87e-3, 1.56e-3, 1.77e-3, 1.49e-3}},
      {"f2", 15000, {4.81e-4, 3.97e-4, 4.81e-4, 3.96e-4, 4.55e-4, 3.77e-4}},
      {"f2", 60000, {1.23e-4, 9.59e-5, 1.23e-4, 9.62e-5, 1.15e-4, 9.03e-5}}};
  for (const Row& r : rows) {
    if (quick && r.n > 15000) continue;
    const test::Heightfield h = test::heightfield(r.f, r.n);
    curvature::Options o;
    o.vertex_normals = &h.normals;
    std::printf("  %s %5d:", r.f, r.n);
    int col = 0;
    for (const Estimator& e : estimators()) {
      const CurvatureField f = e.fn(h.mesh, o);
      const double mh = test::mse(f.H, h.H, h.inner), mk = test::mse(f.K, h.K, h.inner);
      const std::string n(e.name);
      const int a = n == "prantl3" ? 0 : n == "prantl2" ? 2 : n == "rusinkiewicz" ? 4 : -1;
      if (a >= 0)
        std::printf(" %s %.2e/%.2e [%.2e/%.2e]", e.name, mh, mk, r.a[a], r.a[a + 1]);
      else
        std::printf(" %s %.2e/%.2e", e.name, mh, mk);
      ++col;
    }
    std::printf("\n");
  }
}

// vtkCurvatures' mean and Gaussian curvature.
std::pair<std::vector<float>, std::vector<float>> vtk_curvatures(const Mesh& m) {
  auto poly = io::to_polydata(m, nullptr);
  std::vector<float> H(m.vertex_count()), K(m.vertex_count());
  for (int type : {VTK_CURVATURE_MEAN, VTK_CURVATURE_GAUSS}) {
    vtkNew<vtkCurvatures> c;
    c->SetInputData(poly);
    c->SetCurvatureType(type);
    c->Update();
    vtkDataArray* a = c->GetOutput()->GetPointData()->GetScalars();
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
      (type == VTK_CURVATURE_MEAN ? H : K)[i] = float(a->GetTuple1(i));
  }
  return {H, K};
}

// Marching-cubes meshes of analytic fields, volume-gradient normals: relative RMS of H / K
// against the exact values at each vertex's projection (interior vertices).
void marching_cubes_protocol() {
  std::printf("\nMarching cubes (isocurv, snap 0.01), volume-gradient normals: relative RMS H / K "
              "[Appendix A4: vtkMarchingCubes + exact-gradient normals; rusinkiewicz, batagelo, "
              "prantl3]\n");
  openvdb::initialize();
  struct Case {
    const char* field;
    int res;
    double a[6];
  };
  const Case cases[] = {{"torus", 32, {0.0230, 0.0733, 0.0303, 0.0526, 0.0204, 0.0639}},
                        {"torus", 64, {0.0104, 0.0327, 0.0134, 0.0237, 0.0094, 0.0284}},
                        {"torus", 128, {0.0053, 0.0165, 0.0068, 0.0120, 0.0049, 0.0148}},
                        {"sphere", 64, {-1, -1, -1, -1, -1, -1}},
                        {"gyroid", 64, {-1, -1, -1, -1, -1, -1}}};
  for (const Case& c : cases) {
    const auto field = datasets::make_field(c.field);
    const volume::Volume vol = datasets::sample(*field, c.res);
    const Mesh m = mc::extract(vol, float(field->isovalue()), Device::default_device());
    const std::vector<Vec3f> n = volume::gradient_normals(vol, m.positions);
    curvature::Options o;
    o.vertex_normals = &n;
    std::vector<double> eh, ek;
    for (const Vec3f& p : m.positions) {
      const Eigen::Vector3d q =
          datasets::project_to_surface(*field, Eigen::Vector3d(p[0], p[1], p[2]));
      const datasets::SurfaceCurvature s = datasets::exact_curvature(*field, q);
      eh.push_back(s.H), ek.push_back(s.K);
    }
    std::printf("  %-6s %3d^3 (%zu v):", c.field, c.res, m.vertex_count());
    auto report = [&](const char* name, const std::vector<float>& H, const std::vector<float>& K,
                      const std::vector<std::uint8_t>& boundary, double ah, double ak) {
      std::vector<double> h, k, xh, xk;
      for (std::size_t i = 0; i < H.size(); ++i)
        if (boundary.empty() || !boundary[i])
          h.push_back(H[i]), k.push_back(K[i]), xh.push_back(eh[i]), xk.push_back(ek[i]);
      std::printf(" %s %.4f/%.4f", name, test::relative_rms(h, xh), test::relative_rms(k, xk));
      if (ah >= 0) std::printf(" [%.4f/%.4f]", ah, ak);
    };
    for (const Estimator& e : estimators()) {
      const CurvatureField f = e.fn(m, o);
      const std::string s(e.name);
      const int a = s == "rusinkiewicz" ? 0 : s == "batagelo" ? 2 : s == "prantl3" ? 4 : -1;
      report(e.name, f.H, f.K, f.boundary, a >= 0 ? c.a[a] : -1, a >= 0 ? c.a[a + 1] : -1);
    }
    const auto [vh, vk] = vtk_curvatures(m);
    report("vtkCurvatures", vh, vk, {}, -1, -1);
    std::printf("\n");
  }
}

// One speed row: the kernel paths' median time on `m`, beside estimate() and vtkCurvatures.
void speed_row(const char* name, const Mesh& m, int runs) {
  Device& dev = Device::default_device();
  auto poly = io::to_polydata(m, nullptr);
  auto vtk = [&](int type) {
    vtkNew<vtkCurvatures> c;
    c->SetInputData(poly);
    c->SetCurvatureType(type);
    c->Update();
  };
  const std::vector<double> t = bench::medians_ms(
      {{[&] { curvature::estimate(m, dev); }, runs},
       {[&] { curvature::estimate_batagelo(m, dev); }, runs},
       {[&] { curvature::estimate_prantl(m, dev, {}, 3); }, runs},
       {[&] { curvature::estimate_prantl(m, dev, {}, 2); }, runs},
       {[&] {
          vtk(VTK_CURVATURE_MEAN);
          vtk(VTK_CURVATURE_GAUSS);
        },
        std::max(1, runs / 2)}});
  curvature::Timings r, b, p3, p2;
  curvature::estimate(m, dev, {}, &r);
  curvature::estimate_batagelo(m, dev, {}, &b);
  curvature::estimate_prantl(m, dev, {}, 3, curvature::PrantlAveraging::area, &p3);
  curvature::estimate_prantl(m, dev, {}, 2, curvature::PrantlAveraging::area, &p2);
  const double r_steps = r.normals_areas + r.tensor + r.directions;
  const double b_steps = b.normals_areas + b.tensor + b.directions;
  const double p3_steps = p3.normals_areas + p3.tensor + p3.directions;
  const double p2_steps = p2.normals_areas + p2.tensor + p2.directions;
  std::printf("  %-14s %8zu v: whole call rusinkiewicz %.1f | batagelo %.1f | prantl3 %.1f | "
              "prantl2 %.1f | vtkCurvatures H+K %.1f\n",
              name, m.vertex_count(), t[0], t[1], t[2], t[3], t[4]);
  std::printf("  %-25s normals+tensor+directions: rusinkiewicz %.1f | batagelo %.1f (%.2fx) | "
              "prantl3 %.1f (%.2fx) | prantl2 %.1f (%.2fx); derivative: rusinkiewicz %.1f, "
              "batagelo %.1f; host adjacency: rusinkiewicz %.1f, batagelo %.1f\n",
              "", r_steps, b_steps, b_steps / r_steps, p3_steps, p3_steps / r_steps, p2_steps,
              p2_steps / r_steps, r.derivative, b.derivative, r.adjacency, b.adjacency);
  auto parts = [](const curvature::Timings& x) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.1f + %.1f + %.1f", x.normals_areas, x.tensor, x.directions);
    return std::string(buf);
  };
  std::printf(
      "  %-25s the steps (normals + tensor + directions): rusinkiewicz %s | batagelo %s | "
      "prantl3 %s | prantl2 %s\n",
      "", parts(r).c_str(), parts(b).c_str(), parts(p3).c_str(), parts(p2).c_str());
  const double per = 1048576.0 / double(m.vertex_count());
  const double mem_r = bench::peak_extra_mib([&] { curvature::estimate(m, dev); });
  const double mem_b = bench::peak_extra_mib([&] { curvature::estimate_batagelo(m, dev); });
  const double mem_p = bench::peak_extra_mib([&] { curvature::estimate_prantl(m, dev); });
  std::printf("  %-25s peak extra memory per vertex (bytes; PoCL's buffers are host memory): "
              "rusinkiewicz %.0f | batagelo %.0f | prantl %.0f\n",
              "", mem_r * per, mem_b * per, mem_p * per);
  std::fflush(stdout);
}

void speed(bool quick) {
  std::printf("\nSpeed (PoCL here), median ms, mesh normals (the step times drain the queue "
              "after each step)\n");
  openvdb::initialize();
  const auto field = datasets::make_field("sphere");
  const volume::Volume vol = datasets::sample(*field, 160);
  speed_row("MC sphere 160^3", mc::extract(vol, float(field->isovalue()), Device::default_device()),
            5);
  struct Grid {
    int nu, nv;
  };
  const Grid grids[] = {{1000, 200}, {2236, 448}, {3536, 708}};  // 0.2M, 1M, 2.5M vertices
  for (const Grid& g : grids) {
    if (quick && g.nu > 1000) break;
    const test::Torus t = test::torus(1, 0.4, g.nu, g.nv, 0.2);
    speed_row("jittered torus", t.mesh, g.nu > 2000 ? 3 : 5);
  }
}

}  // namespace

int main(int argc, char** argv) {
  bench::keep_freed_memory();
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const auto t0 = std::chrono::steady_clock::now();
  torus_protocols();
  derivative_protocol();
  heightfield_protocol(quick);
  marching_cubes_protocol();
  speed(quick);
  std::printf("\n(%.1f s)\n", ms_since(t0) / 1000);
  return 0;
}
