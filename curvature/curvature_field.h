#pragma once
// The per-vertex curvature arrays the curvature stage produces (names as in DESIGN.md).
// Tested in tests/curvature/compare.h, tests/curvature/estimator_protocols.h.
#include <array>
#include <cstdint>
#include <string>
#include <utility>
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
  /// The values of the extra array `name` (the first of that name), or nullptr when there is none.
  const std::vector<float>* find_extra(const std::string& name) const {
    for (const Named& x : extra)
      if (x.name == name) return &x.values;
    return nullptr;
  }

  /// The surface point each vertex stands for, world units, for measure::object_measures to
  /// integrate over: where the volume estimator places the volume's surface (VolumePoint::surface:
  /// the smoothed isosurface along the gradient line, moved out by the smoothing's shrinkage;
  /// VolumePoint::vertex: the vertex moved along its cube edge by the linear interpolation's
  /// error, curvature::edge_surface_points; the vertex itself where it is Unreliable). Empty for
  /// the other estimators; not written to files, not carried through the stages that renumber
  /// vertices (a user checks its size against the mesh's).
  std::vector<Vec3f> surface_points;

  /// How the field was made, as (name, value) text pairs: "estimator" and its parameters
  /// (curvature::estimate_field fills them). Written as string arrays of the VTP's field data.
  std::vector<std::pair<std::string, std::string>> metadata;

  std::size_t size() const { return k1.size(); }
};

}  // namespace isocurv::curvature
