#pragma once
// Surface normals from the volume itself (the default normals of curvature on volume input).
// Tested in tests/volume/test_gradient_normals.cpp, tests/ao/test_ao.cpp.
#include <cstddef>
#include <vector>

#include "core/mesh.h"
#include "volume/volume.h"

namespace isocurv::volume {

/// Unit outward normals at world positions: the gradient by central differences at the voxels
/// (one-sided at the border of a dense volume's domain, which is never read past), interpolated
/// trilinearly and carried to world space through the transform's inverse-transpose Jacobian;
/// outward is the direction of decreasing "insideness": -gradient for Inside::Above, +gradient for
/// Inside::Below. A zero gradient gives a zero vector. Parallel (TBB), deterministic.
std::vector<Vec3f> gradient_normals(const Volume& volume, const Positions& world_positions);

/// A gradient whose length is at most this fraction of the median length over a mesh's vertices
/// is "near zero": its direction is then set by the neighbouring structures, not by the surface.
inline constexpr double kWeakGradientFraction = 0.01;

/// Gradient normals for the vertices of a mesh extracted from `volume`, checked against the mesh.
struct MeshNormals {
  std::vector<Vec3f> normals;  ///< one unit outward normal per vertex (zero where nothing is known)
  std::size_t opposed = 0;     ///< vertices whose gradient normal points against the faces
  std::size_t weak = 0;        ///< vertices whose gradient is near zero (kWeakGradientFraction)
  std::size_t caps = 0;        ///< cap vertices given the box face's normal (`caps` set)
  std::size_t fallbacks() const { return opposed + weak; }
};

/// gradient_normals at the mesh's vertices, except where the gradient cannot be trusted: where it
/// is near zero (kWeakGradientFraction), or where its normal n has n . a <= 0 with a the vertex's
/// area-weighted face normal (area_weighted_normals; thin plates and gaps a voxel wide, where the
/// central differences see the structure beyond). Those vertices take the unit face normal a
/// instead and are counted; a vertex with a zero face normal keeps the gradient's.
/// With `caps` (a mesh extracted with mc::Options::cap from a dense volume), the vertices of the
/// caps, which lie just outside the domain's box (by kMinEdgeFraction of a voxel or less), take
/// the outward normal of the box face (or faces, at an edge or corner) they lie beyond: the
/// gradient there belongs to the data, not to the cap.
MeshNormals gradient_normals_for_mesh(const Volume& volume, const Mesh& mesh, bool caps = false);

}  // namespace isocurv::volume
