#pragma once
// Meshes with known curvature for the curvature tests, built directly (no mesher needed).
#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "curvature/curvature_field.h"

namespace isocurv::test {

/// Each triangle of `m` with its own three corners, as an STL-minded exporter writes them.
inline Mesh unwelded(const Mesh& m) {
  Mesh u;
  for (const Tri& t : m.triangles) {
    const auto base = std::uint32_t(u.positions.size());
    for (std::uint32_t i : t) u.positions.push_back(m.positions[i]);
    u.triangles.push_back({base, base + 1, base + 2});
  }
  return u;
}

/// Icosahedron subdivided `level` times, vertices projected onto the sphere of `radius` about the
/// origin; outward winding. 10 * 4^level + 2 vertices.
Mesh icosphere(int level, float radius = 1.0f);

/// A torus of major radius R and minor radius r about the z axis as an nu x nv grid of quads split
/// into triangles, outward winding. Vertex (i, j) has index j * nu + i and parameters
/// u = 2 pi (i + du) / nu (around z), v = 2 pi (j + dv) / nv (around the tube, v = 0 outermost),
/// where du, dv are pseudo-random in [-jitter, jitter] (0: the regular grid).
struct Torus {
  double R, r;
  int nu, nv;
  Mesh mesh;
  std::vector<double> us, vs;
  double u(std::size_t vertex) const;
  double v(std::size_t vertex) const;
  /// Closed-form k1 = 1/r, k2 = cos v / (R + r cos v) at a vertex (outward normals).
  double k1(std::size_t vertex) const;
  double k2(std::size_t vertex) const;
  Eigen::Vector3d normal(std::size_t vertex) const;   ///< exact outward unit normal
  Eigen::Vector3d tube_dir(std::size_t vertex) const;  ///< unit d/dv: the k1 direction
  /// Exact dk2/ds along tube_dir: the derivative coefficient C122 = dcurv[2] when dir1 = tube_dir.
  double dk2_along_tube(std::size_t vertex) const;
};
Torus torus(double R, double r, int nu, int nv, double jitter = 0);

/// The graph z = f(x, y) over [-half, half]^2 as an n x n grid (open surface, normals up +z).
/// Vertex (i, j) has index j * n + i. f is given as (a, b): z = (a x^2 + b y^2) / 2, so at the
/// origin the principal curvatures are -a and -b (the normal points up, into the concave side
/// of a > 0).
Mesh quadric_patch(int n, float half, float a, float b);

/// The relative RMS of (x - ref): sqrt(sum (x - ref)^2 / sum ref^2).
double relative_rms(const std::vector<double>& x, const std::vector<double>& ref);

/// Byte-wise equality of every array of two fields.
bool bit_identical(const curvature::CurvatureField& a, const curvature::CurvatureField& b);

/// Every float of every array is finite.
bool all_finite(const curvature::CurvatureField& f);

}  // namespace isocurv::test
