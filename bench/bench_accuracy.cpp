// Accuracy benchmark: H and K errors of every estimator against the exact curvature, on smooth
// float fields and the CT-like classes of datasets/ct_like.h (thin tubes, thick slices, binary
// masks, surfaces cut by the box, saddle sheets), beside vtkCurvatures and OpenVDB's
// math::CurvatureStencil on the same surface, with times, from one run. Errors are taken over the
// vertices the default (volume) estimator does not flag Boundary (its support leaves the box, or
// the mesh's open boundary); relative RMS (RMS error / RMS exact), and absolute RMS for the
// binary classes (the figures published for them are absolute). Not a test.
//
//   bench_accuracy [--quick] [--only NAME]
//   bench_accuracy --refine [--quick] [--only NAME]
//
// --refine: the finer-is-better table instead: each class at 1x and 2x resolution (the binary
// torus also at 4x: grid steps 0.5, 0.25, 0.125), the same object, blur and noise per voxel
// (datasets::ct_like_case's refine), the default volume estimator beside fixed world scales.
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
#include <string>

#include "core/cl_device.h"
#include "core/error.h"
#include "curvature/ao_scale.h"
#include "curvature/estimator.h"
#include "datasets/ct_like.h"
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

using Case = datasets::CtCase;

// A smooth float field: the signed distance of a sphere or torus (positive inside).
Case smooth(const std::string& name, const std::function<double(const Eigen::Vector3d&)>& sd,
            std::array<int, 3> dims, std::function<void(const Eigen::Vector3d&, double&, double&)> exact) {
  std::vector<float> data(std::size_t(dims[0]) * dims[1] * dims[2]);
  std::size_t i = 0;
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x) data[i++] = float(sd(Eigen::Vector3d(x, y, z)));
  volume::DenseSource src;
  src.path = "bench";
  src.format = "generated";
  src.voxel_type = "float";
  src.inside = volume::Inside::Above;
  Case c;
  c.name = name;
  c.volume = volume::from_dense(data.data(), dims,
                                openvdb::math::Transform::createLinearTransform(1.0), src);
  c.iso = 0;
  c.exact = std::move(exact);
  return c;
}

struct Err {
  double H = 0, K = 0, absH = 0, absK = 0, ms = 0;
};

// Errors over the kept vertices.
Err errors(const std::vector<double>& H, const std::vector<double>& K,
           const std::vector<double>& eH, const std::vector<double>& eK,
           const std::vector<bool>& keep, double ms) {
  double nh = 0, nk = 0, dh = 0, dk = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < eH.size(); ++i) {
    if (!keep[i]) continue;
    ++n;
    nh += eH[i] * eH[i], nk += eK[i] * eK[i];
    dh += (H[i] - eH[i]) * (H[i] - eH[i]), dk += (K[i] - eK[i]) * (K[i] - eK[i]);
  }
  if (n == 0) return {std::nan(""), std::nan(""), std::nan(""), std::nan(""), ms};
  return {std::sqrt(dh / nh), std::sqrt(dk / nk), std::sqrt(dh / n), std::sqrt(dk / n), ms};
}

void print(const char* what, const Err& e, bool absolute, const std::string& note = "") {
  if (absolute)
    std::printf("  %-30s H %7.2f%% (abs %.4f)  K %7.2f%% (abs %.5f)  %8.1f ms %s\n", what,
                100 * e.H, e.absH, 100 * e.K, e.absK, e.ms, note.c_str());
  else
    std::printf("  %-30s H %7.2f%%  K %7.2f%%  %8.1f ms %s\n", what, 100 * e.H, 100 * e.K, e.ms,
                note.c_str());
  std::fflush(stdout);
}

std::vector<double> as_double(const std::vector<float>& v) {
  return std::vector<double>(v.begin(), v.end());
}

// The exact H and K of `c` at each vertex of `mesh`.
void exact_at_vertices(const Case& c, const Mesh& mesh, std::vector<double>& eH,
                       std::vector<double>& eK) {
  for (const Vec3f& p : mesh.positions) {
    double h, k;
    c.exact(Eigen::Vector3d(p[0], p[1], p[2]), h, k);
    eH.push_back(h), eK.push_back(k);
  }
}

// One line of the summary table.
struct Summary {
  std::string name;
  bool binary = false;
  Err volume, best_mesh, vtk, openvdb;
  std::string best_mesh_name, scale_note;
  std::size_t boundary = 0, vertices = 0, unreliable = 0;
};

Summary run(const Case& c, bool quick) {
  Device& dev = Device::default_device();
  const Mesh mesh = mc::extract(c.volume, c.iso, dev);
  std::vector<double> eH, eK;
  exact_at_vertices(c, mesh, eH, eK);
  const openvdb::Vec3d sp = c.volume.spacing();
  std::printf("%s: %zu vertices, voxel type %s, spacing %g %g %g\n", c.name.c_str(),
              mesh.vertex_count(), c.volume.voxel_type.c_str(), sp[0], sp[1], sp[2]);
  Summary sum;
  sum.name = c.name;
  sum.binary = c.binary;
  sum.vertices = mesh.vertex_count();
  const float ao = curvature::default_ao_scale(mesh);
  const curvature::VolumeSource source{&c.volume, c.iso};

  // The default: the volume estimator at its automatic per-vertex scale. Its Boundary flags
  // choose the vertices every row is measured on.
  curvature::Options vo;
  vo.estimator = curvature::Estimator::volume;
  vo.ao_scale = ao;
  curvature::estimate_field(mesh, source, &dev, vo);  // warm-up (program build)
  curvature::EstimatorReport r;
  auto t0 = Clock::now();
  const curvature::CurvatureField vf = curvature::estimate_field(mesh, source, &dev, vo, &r);
  const double vms = ms_since(t0);
  std::vector<bool> keep(mesh.vertex_count());
  for (std::size_t i = 0; i < keep.size(); ++i) {
    keep[i] = !vf.boundary[i];
    sum.boundary += vf.boundary[i];
  }
  sum.unreliable = r.unreliable;
  {
    std::vector<float> scales;
    for (const auto& x : vf.extra)
      if (x.name == "Scale") scales = x.values;
    std::sort(scales.begin(), scales.end());
    const double voxel = std::cbrt(sp[0] * sp[1] * sp[2]);
    char note[200];
    auto at = [&](double q) { return scales.empty() ? 0.0 : scales[std::size_t(q * (scales.size() - 1))] / voxel; };
    std::snprintf(note, sizeof note,
                  "(scale p5/p50/p95 %.2f/%.2f/%.2f voxels; %zu finer, %zu unreliable, %zu "
                  "boundary of %zu)",
                  at(0.05), at(0.5), at(0.95), r.finer_scale, r.unreliable, sum.boundary,
                  mesh.vertex_count());
    sum.scale_note = note;
  }
  sum.volume = errors(as_double(vf.H), as_double(vf.K), eH, eK, keep, vms);

  sum.best_mesh.H = 1e9;
  for (const std::string& name : curvature::estimator_names()) {
    if (name == "volume") continue;
    curvature::Options o;
    o.estimator = *curvature::estimator_from_name(name);
    o.ao_scale = ao;
    curvature::estimate_field(mesh, source, &dev, o);  // warm-up
    t0 = Clock::now();
    const auto f = curvature::estimate_field(mesh, source, &dev, o);
    const Err e = errors(as_double(f.H), as_double(f.K), eH, eK, keep, ms_since(t0));
    print((name + ", mesh normals").c_str(), e, c.binary);
    if (e.H < sum.best_mesh.H) sum.best_mesh = e, sum.best_mesh_name = name;
    if (name == "rusinkiewicz") {
      t0 = Clock::now();
      const volume::MeshNormals n = volume::gradient_normals_for_mesh(c.volume, mesh);
      o.vertex_normals = &n.normals;
      const auto g = curvature::estimate_field(mesh, source, &dev, o);
      const Err eg = errors(as_double(g.H), as_double(g.K), eH, eK, keep, ms_since(t0));
      print("rusinkiewicz, volume normals", eg, c.binary);
      if (eg.H < sum.best_mesh.H) sum.best_mesh = eg, sum.best_mesh_name = "rusinkiewicz+vn";
    }
  }
  const std::vector<double> voxels =
      quick ? std::vector<double>{1, 2} : std::vector<double>{0.8, 1, 1.5, 2, 3};
  const double voxel = std::cbrt(sp[0] * sp[1] * sp[2]);
  for (double v : voxels) {
    curvature::Options o = vo;
    o.scale = std::max(v * voxel, 0.66 * std::max({sp[0], sp[1], sp[2]}));
    curvature::EstimatorReport fr;
    t0 = Clock::now();
    const auto f = curvature::estimate_field(mesh, source, &dev, o, &fr);
    const Err e = errors(as_double(f.H), as_double(f.K), eH, eK, keep, ms_since(t0));
    char what[64];
    std::snprintf(what, sizeof what, "volume, scale %.1f voxels", o.scale / voxel);
    print(what, e, c.binary, "(" + std::to_string(fr.finer_scale) + " finer)");
  }
  print("volume, default (auto)", sum.volume, c.binary, sum.scale_note);
  {
    auto poly = io::to_polydata(mesh, nullptr);
    std::vector<double> H(mesh.vertex_count()), K(mesh.vertex_count());
    t0 = Clock::now();
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
    sum.vtk = errors(H, K, eH, eK, keep, ms_since(t0));
    print("vtkCurvatures", sum.vtk, c.binary);
  }
  {
    // OpenVDB's CurvatureStencil (central differences on the grid) at the 8 voxels around each
    // vertex, interpolated trilinearly. Its sign is that of a level set; densities flip H.
    t0 = Clock::now();
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
    sum.openvdb = errors(H, K, eH, eK, keep, ms_since(t0));
    print("OpenVDB CurvatureStencil", sum.openvdb, c.binary);
  }
  std::printf("\n");
  return sum;
}

// One row of the --refine table: the default and fixed world scales on one class at one refine.
void refine_row(const std::string& name, int refine, bool quick) {
  const Case c = datasets::ct_like_case(name, quick, refine);
  Device& dev = Device::default_device();
  const Mesh mesh = mc::extract(c.volume, c.iso, dev);
  std::vector<double> eH, eK;
  exact_at_vertices(c, mesh, eH, eK);
  const curvature::VolumeSource source{&c.volume, c.iso};
  curvature::Options vo;
  vo.estimator = curvature::Estimator::volume;
  vo.ao_scale = curvature::default_ao_scale(mesh);
  curvature::estimate_field(mesh, source, &dev, vo);  // warm-up
  auto t0 = Clock::now();
  const curvature::CurvatureField vf = curvature::estimate_field(mesh, source, &dev, vo);
  const double ms = ms_since(t0);
  std::vector<bool> keep(mesh.vertex_count());
  for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = !vf.boundary[i];
  const openvdb::Vec3d sp = c.volume.spacing();
  const double voxel = std::cbrt(sp[0] * sp[1] * sp[2]);
  std::vector<float> scales;
  for (const auto& x : vf.extra)
    if (x.name == "Scale") scales = x.values;
  std::sort(scales.begin(), scales.end());
  auto at = [&](double q) { return scales.empty() ? 0.0 : double(scales[std::size_t(q * (scales.size() - 1))]); };
  char what[96], note[160];
  std::snprintf(what, sizeof what, "%s x%d (h %.3g, %zu vertices) default", name.c_str(), refine,
                voxel, mesh.vertex_count());
  std::snprintf(note, sizeof note, "(scale p5/p50/p95 %.3g/%.3g/%.3g world, %.2f/%.2f/%.2f voxels)",
                at(0.05), at(0.5), at(0.95), at(0.05) / voxel, at(0.5) / voxel, at(0.95) / voxel);
  print(what, errors(as_double(vf.H), as_double(vf.K), eH, eK, keep, ms), true, note);
  for (double world : {0.35, 0.5, 0.7, 1.0, 1.4, 2.0, 2.8, 4.0, 5.6}) {
    curvature::Options o = vo;
    o.scale = world;
    try {
      t0 = Clock::now();
      const auto f = curvature::estimate_field(mesh, source, &dev, o);
      std::snprintf(what, sizeof what, "  fixed %.2f world (%.2f voxels)", world, world / voxel);
      print(what, errors(as_double(f.H), as_double(f.K), eH, eK, keep, ms_since(t0)), true);
    } catch (const Error&) {
      // outside the estimator's range at this grid
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  openvdb::initialize();
  bool quick = false, refine = false;
  std::string only;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) quick = true;
    else if (!std::strcmp(argv[i], "--refine")) refine = true;
    else if (!std::strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
    else {
      std::fprintf(stderr, "usage: bench_accuracy [--quick] [--refine] [--only NAME]\n");
      return 2;
    }
  }
  if (refine) {
    std::printf("finer is better: each class at 1x and 2x (the same object, blur and noise per "
                "voxel); errors over the vertices not flagged Boundary, relative RMS and absolute "
                "RMS\n\n");
    for (const std::string name :
         {"sphere_u8", "torus_u8", "tube_u8", "torus_binary", "sphere_binary", "part_binary"}) {
      if (!only.empty() && name != only) continue;
      for (int r : {1, 2, 4}) {
        if (r == 4 && name != "torus_binary") continue;
        refine_row(name, r, quick);
      }
      std::printf("\n");
    }
    return 0;
  }
  const int n = quick ? 64 : 128;
  const double R = quick ? 20 : 40;  // sphere radius, voxels
  const Eigen::Vector3d c0(n / 2 + 0.31, n / 2 - 0.17, n / 2 + 0.07);
  const double Rt = quick ? 18 : 36, r = quick ? 7 : 14;
  const std::array<int, 3> tdims = {int(2 * (Rt + r) + 16), int(2 * (Rt + r) + 16),
                                    int(2 * r + 16)};
  const Eigen::Vector3d tc(tdims[0] / 2 + 0.23, tdims[1] / 2 - 0.11, tdims[2] / 2 + 0.17);
  std::vector<std::function<Case()>> cases;
  cases.push_back([&] {
    return smooth("sphere_float", [&](const Eigen::Vector3d& p) { return R - (p - c0).norm(); },
                  {n, n, n}, [R](const Eigen::Vector3d&, double& h, double& k) {
                    h = 1 / R, k = 1 / (R * R);
                  });
  });
  cases.push_back([&] {
    return smooth(
        "torus_float",
        [=](const Eigen::Vector3d& p) {
          const Eigen::Vector3d d = p - tc;
          return r - std::hypot(std::hypot(d.x(), d.y()) - Rt, d.z());
        },
        tdims, [=](const Eigen::Vector3d& p, double& h, double& k) {
          const Eigen::Vector3d d = p - tc;
          const double rho = std::hypot(d.x(), d.y()) - Rt, cosv = rho / std::hypot(rho, d.z());
          const double k1 = 1 / r, k2 = cosv / (Rt + r * cosv);
          h = (k1 + k2) / 2, k = k1 * k2;
        });
  });
  for (const std::string& name : datasets::ct_like_names())
    cases.push_back([name, quick] { return datasets::ct_like_case(name, quick); });
  std::printf(
      "device: %s; errors over the vertices not flagged Boundary, relative to the RMS of the "
      "exact value (absolute RMS too for binary classes)\n\n",
      Device::default_device().info().name.c_str());
  std::vector<Summary> rows;
  for (const auto& make : cases) {
    const Case c = make();
    if (!only.empty() && c.name != only) continue;
    rows.push_back(run(c, quick));
  }
  std::printf("summary (H / K relative RMS; binary: absolute RMS)\n");
  std::printf("%-20s %-17s %-17s %-26s %-17s %-17s\n", "class", "volume (default)",
              "best mesh", "", "vtkCurvatures", "OpenVDB stencil");
  for (const Summary& s : rows) {
    auto cell = [&](const Err& e) {
      char b[40];
      if (s.binary) std::snprintf(b, sizeof b, "%.4f / %.4f", e.absH, e.absK);
      else std::snprintf(b, sizeof b, "%.2f%% / %.2f%%", 100 * e.H, 100 * e.K);
      return std::string(b);
    };
    std::printf("%-20s %-17s %-17s %-26s %-17s %-17s\n", s.name.c_str(), cell(s.volume).c_str(),
                cell(s.best_mesh).c_str(), ("(" + s.best_mesh_name + ")").c_str(),
                cell(s.vtk).c_str(), cell(s.openvdb).c_str());
  }
  return 0;
}
