#pragma once
// The per-vertex curvature arrays the curvature stage produces (names as in DESIGN.md).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh.h"

namespace isocurv::curvature {

/// Per-vertex curvature of a Mesh; every vector has one entry per mesh vertex. Units: world
/// lengths; curvatures in 1/length. Sign: normals point out of the object, so a solid sphere of
/// radius R has k1 = k2 = H = +1/R. An array the estimator does not fill is empty (absent from
/// output files), never zeros (curvature::arrays_filled).
struct CurvatureField {
  std::vector<Vec3f> normals;                ///< "Normals": unit outward normal
  std::vector<float> area;                   ///< "Area": mixed Voronoi area (Meyer et al.)
  std::vector<float> k1, k2;                 ///< "k1", "k2": principal curvatures, k1 >= k2
  std::vector<Vec3f> dir1, dir2;             ///< "dir1", "dir2": unit tangent principal directions
  std::vector<float> H, K;                   ///< "H" = (k1+k2)/2, "K" = k1*k2
  std::vector<std::array<float, 4>> dcurv;   ///< "dcurv": curvature derivative coefficients
  std::vector<float> shape_index;            ///< "ShapeIndex" (Koenderink), in [-1, 1]
  std::vector<float> curvedness;             ///< "Curvedness" = sqrt((k1^2+k2^2)/2)
  std::vector<float> ao;                     ///< "AO": curvature-based ambient occlusion in [0, 1]
  std::vector<std::uint8_t> boundary;        ///< "Boundary": 1 on open-boundary vertices
  std::vector<std::uint8_t> unreliable;      ///< "Unreliable": 1 where the estimator could not
                                             ///< measure (volume: vanishing gradient); absent for
                                             ///< estimators that always can
  /// More per-vertex scalar arrays, by name, from the stages after curvature (features/: "LBE",
  /// "H_ii_r4", ...), written after the arrays above; each empty or one value per vertex.
  struct Named {
    std::string name;
    std::vector<float> values;
  };
  std::vector<Named> extra;

  std::size_t size() const { return k1.size(); }
};

}  // namespace isocurv::curvature
