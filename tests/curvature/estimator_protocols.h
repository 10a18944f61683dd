#pragma once
// The seed papers' evaluation protocols (SEEDS-SPEC 3.2, 4.2, Appendix A) as mesh generators and
// error measures, shared by the estimator tests and bench/bench_estimators.
#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "test_meshes.h"

namespace isocurv::test {

/// Batagelo Fig. 3: the regular torus(R, r, nu, nv) with every vertex moved along its exact
/// normal by U(-d, d) * r (a fixed pseudo-random sequence, seed `seed`); the exact values of the
/// undisplaced torus are kept (as the paper does).
Torus displaced_torus(double R, double r, int nu, int nv, double d, std::uint32_t seed = 7);

/// The exact outward unit normals of a torus mesh (its vertices' parameters).
std::vector<Vec3f> exact_normals(const Torus& t);

/// Absolute RMS of (K - exact K) over the torus's vertices.
double torus_rms_K(const curvature::CurvatureField& f, const Torus& t);

/// Prantl 4.1's height fields on [-10, 10]^2: f1 = 10 sin(r)/r, f2 = sin x cos y + 0.1 (x^2 - y^2).
struct Heightfield {
  std::string name;  ///< "f1" or "f2"
  Mesh mesh;         ///< vtkDelaunay2D of the points in the xy plane, wound with normals up
  std::vector<Vec3f> normals;  ///< exact (-f_x, -f_y, 1) / W
  std::vector<double> H, K;    ///< exact, outward (up) normals
  std::vector<bool> inner;     ///< |x|, |y| < 9 (the protocol's evaluation region)
};
/// `points` uniform random points (fixed `seed`) plus nothing else; the mesh is the Delaunay
/// triangulation of their xy positions.
Heightfield heightfield(const std::string& name, int points, std::uint32_t seed = 11);

/// Mean squared error of x against ref over the vertices where keep is true.
double mse(const std::vector<float>& x, const std::vector<double>& ref,
           const std::vector<bool>& keep);

}  // namespace isocurv::test
