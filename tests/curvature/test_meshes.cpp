#include "test_meshes.h"

#include <cmath>
#include <cstring>
#include <map>
#include <utility>

namespace isocurv::test {

Mesh icosphere(int level, float radius) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Eigen::Vector3d> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                    {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                    {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  Triangles f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& q : p) q.normalize();
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      p.push_back((p[a] + p[b]).normalized());
      return mid[key] = std::uint32_t(p.size() - 1);
    };
    Triangles g;
    for (const Tri& q : f) {
      const std::uint32_t ab = midpoint(q[0], q[1]), bc = midpoint(q[1], q[2]);
      const std::uint32_t ca = midpoint(q[2], q[0]);
      g.push_back({q[0], ab, ca});
      g.push_back({q[1], bc, ab});
      g.push_back({q[2], ca, bc});
      g.push_back({ab, bc, ca});
    }
    f.swap(g);
  }
  Mesh m;
  for (const auto& q : p)
    m.positions.push_back({float(radius * q.x()), float(radius * q.y()), float(radius * q.z())});
  m.triangles = f;
  return m;
}

double Torus::u(std::size_t i) const { return us[i]; }
double Torus::v(std::size_t i) const { return vs[i]; }
double Torus::k1(std::size_t) const { return 1 / r; }
double Torus::k2(std::size_t i) const { return std::cos(v(i)) / (R + r * std::cos(v(i))); }
Eigen::Vector3d Torus::normal(std::size_t i) const {
  return {std::cos(v(i)) * std::cos(u(i)), std::cos(v(i)) * std::sin(u(i)), std::sin(v(i))};
}
Eigen::Vector3d Torus::tube_dir(std::size_t i) const {
  return {-std::sin(v(i)) * std::cos(u(i)), -std::sin(v(i)) * std::sin(u(i)), std::cos(v(i))};
}
double Torus::dk2_along_tube(std::size_t i) const {
  const double d = R + r * std::cos(v(i));
  return -R * std::sin(v(i)) / (r * d * d);
}

Torus torus(double R, double r, int nu, int nv, double jitter) {
  Torus t{R, r, nu, nv, {}, {}, {}};
  std::uint32_t state = 12345;
  auto random = [&]() {  // uniform in [-1, 1], the same sequence on every platform
    state = state * 1664525u + 1013904223u;
    return (state >> 8) / double(1 << 23) - 1;
  };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double u = 2 * M_PI * (i + jitter * random()) / nu;
      const double v = 2 * M_PI * (j + jitter * random()) / nv;
      t.us.push_back(u), t.vs.push_back(v);
      const double rho = R + r * std::cos(v);
      t.mesh.positions.push_back(
          {float(rho * std::cos(u)), float(rho * std::sin(u)), float(r * std::sin(v))});
    }
  auto id = [&](int i, int j) { return std::uint32_t((j % nv) * nu + (i % nu)); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const std::uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      t.mesh.triangles.push_back({a, b, c});
      t.mesh.triangles.push_back({a, c, d});
    }
  return t;
}

Mesh quadric_patch(int n, float half, float a, float b) {
  Mesh m;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = -half + 2.0 * half * i / (n - 1), y = -half + 2.0 * half * j / (n - 1);
      m.positions.push_back({float(x), float(y), float((a * x * x + b * y * y) / 2)});
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const std::uint32_t p = j * n + i, q = p + 1, r = p + n + 1, s = p + n;
      m.triangles.push_back({p, q, r});
      m.triangles.push_back({p, r, s});
    }
  return m;
}

double relative_rms(const std::vector<double>& x, const std::vector<double>& ref) {
  double num = 0, den = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    num += (x[i] - ref[i]) * (x[i] - ref[i]);
    den += ref[i] * ref[i];
  }
  return den > 0 ? std::sqrt(num / den) : std::sqrt(num);
}

namespace {
template <class T>
bool same(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}
template <class T>
bool finite(const std::vector<T>& v) {
  const float* p = reinterpret_cast<const float*>(v.data());
  for (std::size_t i = 0; i < v.size() * sizeof(T) / sizeof(float); ++i)
    if (!std::isfinite(p[i])) return false;
  return true;
}
}  // namespace

bool bit_identical(const curvature::CurvatureField& a, const curvature::CurvatureField& b) {
  return same(a.normals, b.normals) && same(a.area, b.area) && same(a.k1, b.k1) &&
         same(a.k2, b.k2) &&
         same(a.dir1, b.dir1) && same(a.dir2, b.dir2) && same(a.H, b.H) && same(a.K, b.K) &&
         same(a.dcurv, b.dcurv) && same(a.shape_index, b.shape_index) &&
         same(a.curvedness, b.curvedness) && same(a.ao, b.ao) && same(a.boundary, b.boundary);
}

bool all_finite(const curvature::CurvatureField& f) {
  return finite(f.normals) && finite(f.area) && finite(f.k1) && finite(f.k2) && finite(f.dir1) &&
         finite(f.dir2) && finite(f.H) && finite(f.K) && finite(f.dcurv) && finite(f.shape_index) &&
         finite(f.curvedness) && finite(f.ao);
}

}  // namespace isocurv::test
