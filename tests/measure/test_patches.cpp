// measure::object_measures' curved path on meshes built by hand: a geodesic sphere with its exact
// normals (the quadratic patches recover the sphere's area and volume far better than the flat
// triangles), the field's surface points taken over the vertices, and H and K integrated over the
// patches.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <utility>

#include "measure/object_measures.h"

namespace isocurv::measure {
namespace {

/// An octahedron subdivided `levels` times, projected onto the sphere of radius r at c, outward.
Mesh geodesic_sphere(int levels, double r, const Vec3f& c) {
  Mesh m;
  std::vector<std::array<double, 3>> p = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                          {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::vector<Tri> t = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                        {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      std::array<double, 3> q;
      for (int k = 0; k < 3; ++k) q[k] = 0.5 * (p[a][k] + p[b][k]);
      const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
      for (double& v : q) v /= n;
      p.push_back(q);
      return mid[key] = std::uint32_t(p.size() - 1);
    };
    std::vector<Tri> next;
    for (const Tri& f : t) {
      const std::uint32_t a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]),
                          d = midpoint(f[2], f[0]);
      next.insert(next.end(), {Tri{f[0], a, d}, Tri{a, f[1], b}, Tri{d, b, f[2]}, Tri{a, b, d}});
    }
    t.swap(next);
  }
  for (const auto& q : p)
    m.positions.push_back({float(c[0] + r * q[0]), float(c[1] + r * q[1]), float(c[2] + r * q[2])});
  m.triangles.assign(t.begin(), t.end());
  return m;
}

curvature::CurvatureField sphere_field(const Mesh& m, double r, const Vec3f& c, bool normals) {
  curvature::CurvatureField f;
  const std::size_t n = m.positions.size();
  f.H.assign(n, float(1 / r));
  f.K.assign(n, float(1 / (r * r)));
  if (normals)
    for (const Vec3f& p : m.positions) {
      const double x = p[0] - c[0], y = p[1] - c[1], z = p[2] - c[2];
      const double l = std::sqrt(x * x + y * y + z * z);
      f.normals.push_back({float(x / l), float(y / l), float(z / l)});
    }
  return f;
}

TEST(ObjectMeasurePatches, SphereFromItsNormals) {
  const double r = 12;
  const Vec3f c{3, -2, 40};  // away from the origin: the volume is taken about the first vertex
  const Mesh m = geodesic_sphere(3, r, c);  // 512 triangles, edges of about 2.4 for radius 12
  const double area = 4 * M_PI * r * r, volume = 4 * M_PI * r * r * r / 3;
  const ObjectMeasures flat = object_measures(m, sphere_field(m, r, c, false))[0];
  const ObjectMeasures curved = object_measures(m, sphere_field(m, r, c, true))[0];
  // Flat triangles: chords, -1.3% area and -2.3% volume at this size (the sagitta of an edge d
  // is |d|^2 / 8 r). The patches bulge to the sphere: +0.002% area, +0.003% volume (the
  // quadratic edge curves' fourth-order excess); bounds of 0.02%.
  EXPECT_LT(flat.area / area - 1, -0.005);
  EXPECT_LT(flat.volume / volume - 1, -0.01);
  EXPECT_NEAR(curved.area / area - 1, 0, 2e-4);
  EXPECT_NEAR(curved.volume / volume - 1, 0, 2e-4);
  // H over the patches: the integral of the exact curvature. K is the per-vertex curvature's own
  // total on both paths (times the vertices' areas: a third of the flat triangles' here), so the
  // gap says what the sphere's exact K does on this mesh's areas, -1.3%, not the patches.
  EXPECT_NEAR(curved.integral_H / (4 * M_PI * r) - 1, 0, 2e-4);
  EXPECT_DOUBLE_EQ(curved.integral_K, flat.integral_K);
  EXPECT_NEAR(curved.gauss_bonnet_gap(), flat.area / area - 1, 1e-7);
  EXPECT_EQ(curved.euler, 2);
  EXPECT_EQ(curved.edges, flat.edges);
}

TEST(ObjectMeasurePatches, SurfacePointsAreIntegratedAndTheBoxStaysTheMeshs) {
  const Vec3f c{0, 0, 0};
  const Mesh m = geodesic_sphere(2, 1, c);
  curvature::CurvatureField f = sphere_field(m, 1, c, true);
  // Surface points 10% out: area x 1.21, volume x 1.331 (within kMaxSurfaceChange).
  for (const Vec3f& p : m.positions) f.surface_points.push_back({1.1f * p[0], 1.1f * p[1], 1.1f * p[2]});
  const ObjectMeasures larger = object_measures(m, f)[0];
  EXPECT_FALSE(larger.on_vertices);
  // Twice as far: area x 4, more than kMaxSurfaceChange allows: measured over the vertices.
  curvature::CurvatureField g = f;
  for (Vec3f& p : g.surface_points) p = {2 * p[0] / 1.1f, 2 * p[1] / 1.1f, 2 * p[2] / 1.1f};
  const ObjectMeasures twice = object_measures(m, g)[0];
  f.surface_points.clear();
  const ObjectMeasures once = object_measures(m, f)[0];
  EXPECT_NEAR(larger.area, 1.21 * once.area, 1e-6 * once.area);
  EXPECT_NEAR(larger.volume, 1.331 * once.volume, 1e-6 * once.volume);
  EXPECT_EQ(larger.box, once.box);
  EXPECT_EQ(larger.euler, once.euler);
  EXPECT_TRUE(twice.on_vertices);
  EXPECT_EQ(twice.area, once.area);
  EXPECT_EQ(twice.volume, once.volume);
  // Surface points of another mesh (a later stage renumbered the vertices) are ignored.
  f.surface_points.assign(3, Vec3f{9, 9, 9});
  EXPECT_EQ(object_measures(m, f)[0].area, once.area);
}

TEST(ObjectMeasurePatches, BadNormalsFallBackToFlatEdges) {
  const Vec3f c{0, 0, 0};
  const Mesh m = geodesic_sphere(2, 1, c);
  curvature::CurvatureField f = sphere_field(m, 1, c, true);
  for (Vec3f& n : f.normals) n = {0, 0, 0};  // no normal anywhere: the flat triangles
  const ObjectMeasures zero = object_measures(m, f)[0];
  const ObjectMeasures flat = object_measures(m, sphere_field(m, 1, c, false))[0];
  EXPECT_NEAR(zero.area, flat.area, 1e-12);
  EXPECT_NEAR(zero.volume, flat.volume, 1e-12);
  f.normals[0] = {NAN, 0, 0};
  EXPECT_TRUE(std::isfinite(object_measures(m, f)[0].area));
}

}  // namespace
}  // namespace isocurv::measure
