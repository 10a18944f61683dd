#pragma once
// Analytic test surfaces with exact curvature (DESIGN.md convention: normals point out, a convex
// surface has positive curvature).
#include <cmath>

#include "core/mesh.h"
#include "curvature/curvature_field.h"

namespace isocurv::test {

struct TestSurface {
  Mesh mesh;
  curvature::CurvatureField field;
};

inline void derive(curvature::CurvatureField& f, float k1, float k2) {
  const float pi = 3.14159265f;
  f.k1.push_back(k1);
  f.k2.push_back(k2);
  f.H.push_back(0.5f * (k1 + k2));
  f.K.push_back(k1 * k2);
  f.shape_index.push_back(k1 == k2 ? (k1 > 0 ? 1.f : -1.f) : 2.f / pi * std::atan((k1 + k2) / (k1 - k2)));
  f.curvedness.push_back(std::sqrt(0.5f * (k1 * k1 + k2 * k2)));
  f.area.push_back(1.f);
  f.dcurv.push_back({0, 0, 0, 0});
  f.boundary.push_back(0);
}

/// Torus around z (major radius R, tube radius r): K > 0 outside, K < 0 inside the hole.
inline TestSurface torus(float R = 1.f, float r = 0.4f, int nu = 96, int nv = 48) {
  TestSurface s;
  const float two_pi = 6.28318531f;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const float u = two_pi * i / nu, v = two_pi * j / nv;
      const float cu = std::cos(u), su = std::sin(u), cv = std::cos(v), sv = std::sin(v);
      s.mesh.positions.push_back({(R + r * cv) * cu, (R + r * cv) * su, r * sv});
      s.field.normals.push_back({cv * cu, cv * su, sv});
      s.field.dir1.push_back({-sv * cu, -sv * su, cv});  // around the tube: k = 1/r
      s.field.dir2.push_back({-su, cu, 0});              // around the axis: k = cos v / (R + r cos v)
      derive(s.field, 1.f / r, cv / (R + r * cv));
      s.field.ao.push_back(0.55f + 0.45f * (0.5f + 0.5f * cv));  // darker inside the hole
    }
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const auto at = [&](int a, int b) { return static_cast<std::uint32_t>((a % nu) * nv + (b % nv)); };
      s.mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      s.mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return s;
}

/// The saddle z = x^2 - y^2 on [-1, 1]^2, outside = +z: H = 4(x^2 - y^2)/W^3 takes both signs,
/// K = -4/W^4 < 0 (W = sqrt(1 + 4x^2 + 4y^2)).
inline TestSurface saddle(int n = 64) {
  TestSurface s;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float x = -1.f + 2.f * i / (n - 1), y = -1.f + 2.f * j / (n - 1);
      const float W = std::sqrt(1 + 4 * x * x + 4 * y * y);
      s.mesh.positions.push_back({x, y, x * x - y * y});
      s.field.normals.push_back({-2 * x / W, 2 * y / W, 1 / W});
      const float H = 4 * (x * x - y * y) / (W * W * W), K = -4 / (W * W * W * W);
      const float d = std::sqrt(H * H - K);
      derive(s.field, H + d, H - d);
      const float lx = std::sqrt(1 + 4 * x * x), ly = std::sqrt(1 + 4 * y * y);
      s.field.dir1.push_back({1 / lx, 0, 2 * x / lx});  // approximately principal: the axis directions
      s.field.dir2.push_back({0, 1 / ly, -2 * y / ly});
      s.field.ao.push_back(1.f - 0.3f * std::fabs(x * y));
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const std::uint32_t a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      s.mesh.triangles.push_back({a, b, d});
      s.mesh.triangles.push_back({a, d, c});
    }
  return s;
}

}  // namespace isocurv::test
