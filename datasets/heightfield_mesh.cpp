#include "datasets/heightfield_mesh.h"

#include <cmath>

#include "core/error.h"

namespace isocurv::datasets {
namespace {

constexpr int kBisections = 60;  // 2^-60 of the box height: far below 1e-12 of it

/// The z in [z0, z1] where field - isovalue changes sign at (x, y).
double crossing(const Field& f, double x, double y, double z0, double z1) {
  auto g = [&](double z) { return f.value(Eigen::Vector3d(x, y, z)) - f.isovalue(); };
  double a = z0, b = z1, ga = g(a), gb = g(b);
  if (!(ga * gb < 0))
    throw Error(f.name() + " is not a heightfield: no single crossing along z at (" +
                std::to_string(x) + ", " + std::to_string(y) + ")");
  for (int i = 0; i < kBisections; ++i) {
    const double m = 0.5 * (a + b), gm = g(m);
    if ((gm < 0) == (ga < 0))
      a = m, ga = gm;
    else
      b = m;
  }
  return 0.5 * (a + b);
}

}  // namespace

Mesh heightfield_mesh(const Field& field, int n) {
  if (n < 2) throw Error("heightfield_mesh: needs at least 2 x 2 vertices");
  const Eigen::AlignedBox3d& box = field.box();
  const Eigen::Vector3d lo = box.min(), hi = box.max();
  Mesh m;
  m.positions.reserve(std::size_t(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = lo.x() + (hi.x() - lo.x()) * i / (n - 1),
                   y = lo.y() + (hi.y() - lo.y()) * j / (n - 1);
      const double z = crossing(field, x, y, lo.z(), hi.z());
      m.positions.push_back({float(x), float(y), float(z)});
    }
  m.triangles.reserve(2 * std::size_t(n - 1) * (n - 1));
  auto at = [n](int i, int j) { return std::uint32_t(i + n * j); };
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {  // counter-clockwise seen from +z
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

}  // namespace isocurv::datasets
