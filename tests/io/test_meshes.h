#pragma once
// Small meshes with every curvature array filled, for the io tests.
#include <cmath>
#include <cstring>
#include <random>

#include "core/mesh.h"
#include "curvature/curvature_field.h"

namespace isocurv::test {

/// An nx-by-ny grid of vertices (a wavy sheet), two CCW triangles per cell.
inline Mesh grid_mesh(int nx = 7, int ny = 5) {
  Mesh m;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      m.positions.push_back({0.1f * i, 0.1f * j, 0.01f * std::sin(float(i + 2 * j))});
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const std::uint32_t a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      m.triangles.push_back({a, b, d});
      m.triangles.push_back({a, d, c});
    }
  return m;
}

/// Every array of the field filled with arbitrary floats (including -0, denormals, huge values),
/// so that an exact round trip means bit-for-bit.
inline curvature::CurvatureField random_field(std::size_t n, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-3.f, 3.f);
  auto value = [&](std::size_t i) {
    switch (i % 11) {
      case 3: return -0.0f;
      case 5: return 1.0e-40f;  // denormal
      case 7: return 3.0e38f;
      default: return u(rng) / 7.f;
    }
  };
  curvature::CurvatureField f;
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i) {
    f.normals.push_back({value(k++), value(k++), value(k++)});
    f.area.push_back(value(k++));
    f.k1.push_back(value(k++));
    f.k2.push_back(value(k++));
    f.dir1.push_back({value(k++), value(k++), value(k++)});
    f.dir2.push_back({value(k++), value(k++), value(k++)});
    f.H.push_back(value(k++));
    f.K.push_back(value(k++));
    f.dcurv.push_back({value(k++), value(k++), value(k++), value(k++)});
    f.shape_index.push_back(value(k++));
    f.curvedness.push_back(value(k++));
    f.ao.push_back(value(k++));
    f.boundary.push_back(static_cast<std::uint8_t>(i % 3 == 0));
  }
  return f;
}

/// Bit-for-bit equality of two vectors of plain values.
template <class T, class A>
bool same_bits(const std::vector<T, A>& a, const std::vector<T, A>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

}  // namespace isocurv::test
