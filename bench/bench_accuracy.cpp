// Accuracy benchmark: H and K errors of every estimator against the exact curvature, on smooth
// float fields and CT-like volumes (an analytic solid with an edge blurred over a voxel,
// quantised to uint8 or uint16, with Gaussian noise), beside vtkCurvatures and OpenVDB's
// math::CurvatureStencil on the same surface, with times, from one run. Not a test.
//
//   bench_accuracy [--quick]
#include <openvdb/math/Stencils.h>
#include <vtkCurvatures.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>

#include "core/cl_device.h"
#include "curvature/ao_scale.h"
#include "curvature/auto_scale.h"
#include "curvature/estimate.h"
#include "curvature/estimator.h"
#include "datasets/exact_curvature.h"
#include "datasets/field.h"
#include "datasets/sample.h"
#include "io/polydata.h"
#include "mc/extract.h"
#include "volume/from_dense.h"
#include "volume/gradient_normals.h"

using namespace isocurv;

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct Case {
  std::string name;
  volume::Volume volume;
  float iso = 0;
  std::function<void(const Eigen::Vector3d&, double&, double&)> exact;  // H, K at a vertex
};

volume::Volume dense(const std::function<double(int, int, int)>& f, std::array<int, 3> dims,
                     const std::string& type, volume::Inside inside) {
  std::vector<float> data(std::size_t(dims[0]) * dims[1] * dims[2]);
  std::size_t i = 0;
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x) data[i++] = float(f(x, y, z));
  volume::DenseSource src;
  src.path = "bench";
  src.format = "generated";
  src.voxel_type = type;
  src.inside = inside;
  return volume::from_dense(data.data(), dims, openvdb::math::Transform::createLinearTransform(1.0),
                            src);
}

// A CT-like volume of a solid whose signed distance (positive inside) is `sd`: grey levels lo and
// hi across an edge blurred over one voxel (erfc profile), noise of `noise` levels, rounded and
// clamped to the type's range.
volume::Volume ct_like(const std::function<double(const Eigen::Vector3d&)>& sd,
                       std::array<int, 3> dims, const std::string& type, double lo, double hi,
                       double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const double top = type == "uint8" ? 255 : 65535;
  return dense(
      [&](int x, int y, int z) {
        const double e = 0.5 * std::erfc(-sd(Eigen::Vector3d(x, y, z)) / std::sqrt(2.0));
        return std::clamp(std::round(lo + (hi - lo) * e + noise * gauss(rng)), 0.0, top);
      },
      dims, type, volume::Inside::Above);
}

struct Err {
  double H = 0, K = 0, H99 = 0, K99 = 0, ms = 0;
};

Err errors(const std::vector<double>& H, const std::vector<double>& K,
           const std::vector<double>& eH, const std::vector<double>& eK, double ms) {
  double nh = 0, nk = 0;
  for (std::size_t i = 0; i < eH.size(); ++i) nh += eH[i] * eH[i], nk += eK[i] * eK[i];
  nh = std::sqrt(nh / eH.size()), nk = std::sqrt(nk / eK.size());
  std::vector<double> dh, dk;
  double sh = 0, sk = 0;
  for (std::size_t i = 0; i < eH.size(); ++i) {
    dh.push_back(std::abs(H[i] - eH[i]) / nh), dk.push_back(std::abs(K[i] - eK[i]) / nk);
    sh += dh.back() * dh.back(), sk += dk.back() * dk.back();
  }
  std::sort(dh.begin(), dh.end()), std::sort(dk.begin(), dk.end());
  const std::size_t p = std::min(dh.size() - 1, std::size_t(0.99 * dh.size()));
  return {std::sqrt(sh / dh.size()), std::sqrt(sk / dk.size()), dh[p], dk[p], ms};
}

void print(const char* what, const Err& e, const std::string& note = "") {
  std::printf("  %-34s H %7.2f%% (p99 %7.2f%%)  K %7.2f%% (p99 %7.2f%%)  %8.1f ms %s\n", what,
              100 * e.H, 100 * e.H99, 100 * e.K, 100 * e.K99, e.ms, note.c_str());
  std::fflush(stdout);
}

void run(const Case& c, bool quick) {
  Device& dev = Device::default_device();
  const Mesh mesh = mc::extract(c.volume, c.iso, dev);
  std::vector<double> eH, eK;
  for (const Vec3f& p : mesh.positions) {
    double h, k;
    c.exact(Eigen::Vector3d(p[0], p[1], p[2]), h, k);
    eH.push_back(h), eK.push_back(k);
  }
  std::printf("%s: %zu vertices, voxel type %s\n", c.name.c_str(), mesh.vertex_count(),
              c.volume.voxel_type.c_str());
  auto as_double = [](const std::vector<float>& v) {
    return std::vector<double>(v.begin(), v.end());
  };
  const float ao = curvature::default_ao_scale(mesh);
  Err best_fixed{1e9, 1e9};
  {
    curvature::Options o;
    o.ao_scale = ao;
    curvature::estimate(mesh, dev, o);  // warm-up (program build)
    auto t0 = Clock::now();
    const auto f = curvature::estimate(mesh, dev, o);
    print("rusinkiewicz, mesh normals",
          errors(as_double(f.H), as_double(f.K), eH, eK, ms_since(t0)));
    t0 = Clock::now();
    const volume::MeshNormals n = volume::gradient_normals_for_mesh(c.volume, mesh);
    o.vertex_normals = &n.normals;
    const auto g = curvature::estimate(mesh, dev, o);
    print("rusinkiewicz, volume normals",
          errors(as_double(g.H), as_double(g.K), eH, eK, ms_since(t0)));
  }
  const std::vector<double> voxels =
      quick ? std::vector<double>{1, 2} : std::vector<double>{0.7, 1, 1.5, 2, 2.5, 3};
  curvature::Options o;
  o.estimator = curvature::Estimator::volume;
  o.ao_scale = ao;
  for (double v : voxels) {
    o.scale = v;
    curvature::estimate_field(mesh, {&c.volume, c.iso}, &dev, o);  // warm-up
    const auto t0 = Clock::now();
    const auto f = curvature::estimate_field(mesh, {&c.volume, c.iso}, &dev, o);
    const Err e = errors(as_double(f.H), as_double(f.K), eH, eK, ms_since(t0));
    char what[64];
    std::snprintf(what, sizeof what, "volume, scale %.1f voxels", v);
    print(what, e);
    if (e.H < best_fixed.H) best_fixed = e;
  }
  {
    o.scale = 0;
    curvature::EstimatorReport r;
    const auto t0 = Clock::now();
    const auto f = curvature::estimate_field(mesh, {&c.volume, c.iso}, &dev, o, &r);
    char note[160];
    double noise = 0, level = 0;
    for (auto& [k, v] : r.parameters) {
      if (k == "noise") noise = v;
      if (k == "noise_level") level = v;
    }
    std::snprintf(note, sizeof note, "(auto: %.2f voxels; noise %.3g, noise level %.3g)",
                  r.parameters.front().second, noise, level);
    print("volume, scale auto", errors(as_double(f.H), as_double(f.K), eH, eK, ms_since(t0)), note);
  }
  {
    auto poly = io::to_polydata(mesh, nullptr);
    std::vector<double> H(mesh.vertex_count()), K(mesh.vertex_count());
    const auto t0 = Clock::now();
    for (int type : {VTK_CURVATURE_MEAN, VTK_CURVATURE_GAUSS}) {
      vtkNew<vtkCurvatures> vc;
      vc->SetInputData(poly);
      vc->SetCurvatureType(type);
      vc->Update();
      vtkDataArray* a = vc->GetOutput()->GetPointData()->GetScalars();
      for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
        (type == VTK_CURVATURE_MEAN ? H : K)[i] = a->GetTuple1(i);
    }
    // vtkCurvatures' mean curvature sign follows the triangles' orientation: align it to ours.
    double dot = 0;
    for (std::size_t i = 0; i < H.size(); ++i) dot += H[i] * eH[i];
    if (dot < 0)
      for (double& h : H) h = -h;
    print("vtkCurvatures", errors(H, K, eH, eK, ms_since(t0)));
  }
  {
    // OpenVDB's CurvatureStencil (central differences on the grid) at the 8 voxels around each
    // vertex, interpolated trilinearly. Its sign is that of a level set; densities flip H.
    const auto t0 = Clock::now();
    const openvdb::FloatGrid& grid = *c.volume.grid;
    openvdb::math::CurvatureStencil<openvdb::FloatGrid> st(grid);
    const double sign = c.volume.inside == volume::Inside::Above ? -1 : 1;
    std::vector<double> H, K;
    for (const Vec3f& p : mesh.positions) {
      const openvdb::Vec3d q = grid.transform().worldToIndex(openvdb::Vec3d(p[0], p[1], p[2]));
      const openvdb::Coord b = openvdb::Coord::floor(q);
      double h = 0, k = 0;
      for (int dz = 0; dz < 2; ++dz)
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx) {
            const double w = (dx ? q[0] - b[0] : 1 - (q[0] - b[0])) *
                             (dy ? q[1] - b[1] : 1 - (q[1] - b[1])) *
                             (dz ? q[2] - b[2] : 1 - (q[2] - b[2]));
            st.moveTo(b.offsetBy(dx, dy, dz));
            float mean = 0, gauss = 0;
            st.curvatures(mean, gauss);
            h += w * mean, k += w * gauss;
          }
      H.push_back(sign * h), K.push_back(k);
    }
    print("OpenVDB CurvatureStencil", errors(H, K, eH, eK, ms_since(t0)));
  }
  std::printf("  best fixed scale: H %.2f%%, K %.2f%%\n\n", 100 * best_fixed.H, 100 * best_fixed.K);
}

}  // namespace

int main(int argc, char** argv) {
  openvdb::initialize();
  bool quick = false;
  for (int i = 1; i < argc; ++i)
    if (!std::strcmp(argv[i], "--quick")) quick = true;
  const int n = quick ? 64 : 128;
  const double R = quick ? 20 : 40;  // sphere radius, voxels
  const Eigen::Vector3d c0(n / 2 + 0.31, n / 2 - 0.17, n / 2 + 0.07);
  auto sphere_exact = [R](const Eigen::Vector3d&, double& h, double& k) {
    h = 1 / R, k = 1 / (R * R);
  };
  // Torus about z through tc: tube radius r, core radius Rt (voxels).
  const double Rt = quick ? 18 : 36, r = quick ? 7 : 14;
  const std::array<int, 3> tdims = {int(2 * (Rt + r) + 16), int(2 * (Rt + r) + 16),
                                    int(2 * r + 16)};
  const Eigen::Vector3d tc(tdims[0] / 2 + 0.23, tdims[1] / 2 - 0.11, tdims[2] / 2 + 0.17);
  auto torus_sd = [=](const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - tc;
    const double rho = std::hypot(d.x(), d.y()) - Rt;
    return r - std::hypot(rho, d.z());
  };
  auto torus_exact = [=](const Eigen::Vector3d& p, double& h, double& k) {
    const Eigen::Vector3d d = p - tc;
    const double rho = std::hypot(d.x(), d.y()) - Rt, cosv = rho / std::hypot(rho, d.z());
    const double k1 = 1 / r, k2 = cosv / (Rt + r * cosv);
    h = (k1 + k2) / 2, k = k1 * k2;
  };
  auto sphere_sd = [=](const Eigen::Vector3d& p) { return R - (p - c0).norm(); };
  std::vector<Case> cases;
  cases.push_back({"sphere float (distance field)",
                   dense([&](int x, int y, int z) { return sphere_sd(Eigen::Vector3d(x, y, z)); },
                         {n, n, n}, "float", volume::Inside::Above),
                   0.0f, sphere_exact});
  cases.push_back({"torus float (distance field)",
                   dense([&](int x, int y, int z) { return torus_sd(Eigen::Vector3d(x, y, z)); },
                         tdims, "float", volume::Inside::Above),
                   0.0f, torus_exact});
  cases.push_back({"sphere CT-like uint8, noise 3",
                   ct_like(sphere_sd, {n, n, n}, "uint8", 20, 220, 3, 1), 120.0f, sphere_exact});
  cases.push_back({"torus CT-like uint8, noise 3", ct_like(torus_sd, tdims, "uint8", 20, 220, 3, 2),
                   120.0f, torus_exact});
  cases.push_back({"sphere CT-like uint8, no noise",
                   ct_like(sphere_sd, {n, n, n}, "uint8", 20, 220, 0, 3), 120.0f, sphere_exact});
  cases.push_back({"sphere CT-like uint16, noise 40",
                   ct_like(sphere_sd, {n, n, n}, "uint16", 1000, 4000, 40, 4), 2500.0f,
                   sphere_exact});
  std::printf(
      "device: %s; errors relative to the RMS of the exact value; p99 of the per-vertex "
      "relative error\n\n",
      Device::default_device().info().name.c_str());
  for (const Case& c : cases) run(c, quick);
  return 0;
}
