#include "estimator_protocols.h"

#include <vtkCellArray.h>
#include <vtkDelaunay2D.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <cmath>
#include <stdexcept>

namespace isocurv::test {
namespace {

// Uniform in [0, 1), the same sequence on every platform (splitmix64).
struct Random {
  std::uint64_t state;
  double next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return double(z >> 11) / double(1ull << 53);
  }
};

// f and its first and second derivatives at (x, y).
struct Jet {
  double f, fx, fy, fxx, fxy, fyy;
};

Jet f1(double x, double y) {
  const double r2 = x * x + y * y, r = std::sqrt(r2);
  if (r < 1e-4) return {10 * (1 - r2 / 6), -10 * x / 3, -10 * y / 3, -10.0 / 3, 0, -10.0 / 3};
  const double s = std::sin(r), c = std::cos(r);
  const double f = 10 * s / r, fr = 10 * (r * c - s) / r2;
  const double frr = 10 * (-r2 * s - 2 * r * c + 2 * s) / (r2 * r);
  return {f,
          fr * x / r,
          fr * y / r,
          frr * x * x / r2 + fr * (1 / r - x * x / (r2 * r)),
          frr * x * y / r2 - fr * x * y / (r2 * r),
          frr * y * y / r2 + fr * (1 / r - y * y / (r2 * r))};
}

Jet f2(double x, double y) {
  const double sx = std::sin(x), cx = std::cos(x), sy = std::sin(y), cy = std::cos(y);
  return {sx * cy + 0.1 * (x * x - y * y), cx * cy + 0.2 * x, -sx * sy - 0.2 * y,
          -sx * cy + 0.2, -cx * sy, -sx * cy - 0.2};
}

}  // namespace

Torus displaced_torus(double R, double r, int nu, int nv, double d, std::uint32_t seed) {
  Torus t = torus(R, r, nu, nv, 0);
  Random rng{seed};
  for (std::size_t i = 0; i < t.mesh.vertex_count(); ++i) {
    const Eigen::Vector3d n = t.normal(i);
    const double s = (2 * rng.next() - 1) * d * r;
    for (int c = 0; c < 3; ++c) t.mesh.positions[i][c] = float(t.mesh.positions[i][c] + s * n[c]);
  }
  return t;
}

std::vector<Vec3f> exact_normals(const Torus& t) {
  std::vector<Vec3f> n;
  for (std::size_t i = 0; i < t.mesh.vertex_count(); ++i) {
    const Eigen::Vector3d v = t.normal(i);
    n.push_back({float(v.x()), float(v.y()), float(v.z())});
  }
  return n;
}

double torus_rms_K(const curvature::CurvatureField& f, const Torus& t) {
  double sum = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double e = f.K[i] - t.k1(i) * t.k2(i);
    sum += e * e;
  }
  return std::sqrt(sum / double(f.size()));
}

Heightfield heightfield(const std::string& name, int points, std::uint32_t seed) {
  if (name != "f1" && name != "f2") throw std::invalid_argument("heightfield: " + name);
  Heightfield h;
  h.name = name;
  Random rng{seed};
  vtkNew<vtkPoints> pts;
  for (int i = 0; i < points; ++i) {
    const double x = 20 * rng.next() - 10, y = 20 * rng.next() - 10;
    const Jet j = name == "f1" ? f1(x, y) : f2(x, y);
    pts->InsertNextPoint(x, y, j.f);
    h.mesh.positions.push_back({float(x), float(y), float(j.f)});
    const double W = std::sqrt(1 + j.fx * j.fx + j.fy * j.fy);
    h.normals.push_back({float(-j.fx / W), float(-j.fy / W), float(1 / W)});
    h.H.push_back(-((1 + j.fx * j.fx) * j.fyy - 2 * j.fx * j.fy * j.fxy + (1 + j.fy * j.fy) * j.fxx) /
                  (2 * W * W * W));
    h.K.push_back((j.fxx * j.fyy - j.fxy * j.fxy) / (W * W * W * W));
    h.inner.push_back(std::abs(x) < 9 && std::abs(y) < 9);
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(pts);
  vtkNew<vtkDelaunay2D> del;
  del->SetInputData(poly);
  del->Update();
  vtkCellArray* cells = del->GetOutput()->GetPolys();
  vtkNew<vtkIdList> ids;
  for (cells->InitTraversal(); cells->GetNextCell(ids);) {
    if (ids->GetNumberOfIds() != 3) continue;
    Tri t{std::uint32_t(ids->GetId(0)), std::uint32_t(ids->GetId(1)), std::uint32_t(ids->GetId(2))};
    const Vec3f &a = h.mesh.positions[t[0]], &b = h.mesh.positions[t[1]],
                &c = h.mesh.positions[t[2]];
    const double cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if (cross < 0) std::swap(t[1], t[2]);
    h.mesh.triangles.push_back(t);
  }
  return h;
}

double mse(const std::vector<float>& x, const std::vector<double>& ref,
           const std::vector<bool>& keep) {
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (keep[i]) sum += (x[i] - ref[i]) * (x[i] - ref[i]), ++n;
  return n ? sum / double(n) : 0;
}

}  // namespace isocurv::test
